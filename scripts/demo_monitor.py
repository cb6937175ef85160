#!/usr/bin/env python3
"""Watches the enhanced ORB pipeline (default mode), the paper preset and the baseline while a bag
plays: prints progress, then a summary table; writes the summary (Markdown and per-frame CSV) and a
few annotated frames, default | paper | baseline side by side, to an output folder. Exits when the
frames stop coming.

What the summary compares is what a visual odometry front end gets from each: matches to the
previous frame (mutual Hamming nearest neighbours) that survive a RANSAC check (fundamental matrix,
1 px), beside keypoints and milliseconds, overall and by the frame's light."""
import argparse
import csv
import os
import sys
import threading
import time

import cv2
import numpy as np
import rospy
from cv_bridge import CvBridge
from diagnostic_msgs.msg import DiagnosticArray
from sensor_msgs.msg import Image

from enhanced_orb.msg import KeypointArray

METHODS = ("default", "paper", "baseline")
TOPICS = {"default": "", "paper": "paper/", "baseline": "baseline/"}
LABELS = {"default": "default mode", "paper": "paper preset", "baseline": "original ORB"}


def ransac_matches(previous, current):
    """Matches of `current` to `previous` that survive RANSAC on the fundamental matrix."""
    if previous is None or len(previous[0]) < 8 or len(current[0]) < 8:
        return 0
    matcher = cv2.BFMatcher(cv2.NORM_HAMMING, crossCheck=True)
    matches = matcher.match(previous[1], current[1])
    if len(matches) < 8:
        return 0
    p1 = np.float32([previous[0][m.queryIdx] for m in matches])
    p2 = np.float32([current[0][m.trainIdx] for m in matches])
    _, mask = cv2.findFundamentalMat(p1, p2, cv2.FM_RANSAC, 1.0, 0.999)
    return int(mask.sum()) if mask is not None else 0


class Monitor:
    def __init__(self, args):
        self.args = args
        self.lock = threading.Lock()
        self.bridge = CvBridge()
        self.rows = {}  # stamp -> {method: (keypoints, extract ms, RANSAC matches to the previous frame)}
        self.previous = {m: None for m in METHODS}  # (points, descriptors) of the last frame
        self.light = {}  # stamp -> mean gray of the raw frame
        self.annotated = {m: {} for m in METHODS}  # stamp -> image, for the frames to save
        self.enhance_ms = {"default": [], "paper": []}  # (frames, mean ms) per diagnostics window
        self.first_stamp = None
        self.last_message = None
        self.saved = []
        self.shown = -1
        cam = args.camera
        for m in METHODS:
            rospy.Subscriber(f"/{cam}/{TOPICS[m]}keypoints", KeypointArray, self.on_keypoints, m, queue_size=50)
            rospy.Subscriber(f"/{cam}/{TOPICS[m]}image_annotated", Image, self.on_annotated, m, queue_size=5,
                             buff_size=2 ** 24)
        rospy.Subscriber(f"/{cam}/image_raw", Image, self.on_raw, queue_size=50, buff_size=2 ** 24)
        rospy.Subscriber("/diagnostics", DiagnosticArray, self.on_diagnostics, queue_size=10)

    def index(self, stamp):
        if self.first_stamp is None:
            self.first_stamp = stamp
        return int(round((stamp - self.first_stamp).to_sec() * self.args.fps))

    def on_raw(self, msg):
        mean = float(np.frombuffer(msg.data, np.uint8).mean()) if msg.encoding == "mono8" else float("nan")
        with self.lock:
            self.light[msg.header.stamp] = mean

    def on_keypoints(self, msg, which):
        points = np.float32([[k.x, k.y] for k in msg.keypoints]).reshape(-1, 2)
        descriptors = np.frombuffer(bytes(msg.descriptors), np.uint8).reshape(-1, max(1, msg.descriptor_bytes))
        current = (points, descriptors)
        with self.lock:
            previous = self.previous[which]
            self.previous[which] = current
        survived = ransac_matches(previous, current)
        with self.lock:
            self.index(msg.header.stamp)
            self.rows.setdefault(msg.header.stamp, {})[which] = (len(msg.keypoints), msg.extract_ms, survived)
            self.last_message = time.monotonic()

    def on_annotated(self, msg, which):
        with self.lock:
            if self.index(msg.header.stamp) not in self.args.save:
                return
            self.annotated[which][msg.header.stamp] = self.bridge.imgmsg_to_cv2(msg, "bgr8")
            self.save_frames()

    def on_diagnostics(self, msg):
        for status in msg.status:
            # diagnostic_updater names a status "<node name without the leading slash>: <task>".
            for method, node in (("default", "enhance"), ("paper", "paper_enhance")):
                if status.name.endswith(f"{self.args.camera}/{node}: processing"):
                    values = {kv.key: kv.value for kv in status.values}
                    frames = float(values.get("frames per second", 0))
                    if frames > 0:
                        with self.lock:
                            self.enhance_ms[method].append((frames, float(values["mean processing time [ms]"])))

    def save_frames(self):
        for stamp in set.intersection(*(set(self.annotated[m]) for m in METHODS)):
            images = [self.annotated[m].pop(stamp) for m in METHODS]
            gap = np.zeros((images[0].shape[0], 8, 3), np.uint8)
            row = np.hstack([images[0], gap, images[1], gap, images[2]])
            for k, m in enumerate(METHODS):
                x = 10 + k * (images[0].shape[1] + 8)
                for colour, thickness in (((0, 0, 0), 4), ((255, 255, 255), 1)):
                    cv2.putText(row, LABELS[m], (x, images[0].shape[0] - 12), cv2.FONT_HERSHEY_SIMPLEX, 0.7, colour,
                                thickness, cv2.LINE_AA)
            path = os.path.join(self.args.output, f"frame_{self.index(stamp):04d}.png")
            cv2.imwrite(path, row)
            self.saved.append(path)

    def complete(self):
        return sorted((s, r) for s, r in self.rows.items() if len(r) == len(METHODS))

    def progress(self):
        with self.lock:
            done = self.complete()
        if len(done) == self.shown:
            return
        tty = sys.stdout.isatty()
        if not tty and len(done) - self.shown < 25 and len(done) < self.args.frames:
            return  # in a log, a line every 25 frames
        self.shown = len(done)
        total = self.args.frames
        width = 30
        filled = int(width * min(len(done), total) / total) if total else 0
        text = f"\r[{'#' * filled}{'.' * (width - filled)}] {len(done):4d}/{total} frames"
        if done:
            last = done[-1][1]
            text += "  RANSAC matches: " + "  ".join(f"{m} {last[m][2]:4d}" for m in METHODS)
        sys.stdout.write(text if tty else text[1:] + "\n")
        sys.stdout.flush()

    def summary(self):
        with self.lock:
            rows = self.complete()
            light = dict(self.light)
            enhance = {m: list(v) for m, v in self.enhance_ms.items()}
        n = len(rows)

        def mean(values):
            return sum(values) / len(values) if values else float("nan")

        def enhance_mean(method):
            frames = sum(f for f, _ in enhance.get(method, []))
            return sum(f * m for f, m in enhance.get(method, [])) / frames if frames else 0.0

        # The darkest quarter of the frames, by the mean gray of what the camera recorded.
        grays = sorted(light.get(s, 255.0) for s, _ in rows)
        cut = grays[len(grays) // 4] if grays else 0.0
        dark = [(s, r) for s, r in rows if light.get(s, 255.0) <= cut]
        header = "| | " + " | ".join(LABELS[m] for m in METHODS) + " |"
        table = [header, "| --- |" + " ---: |" * len(METHODS), f"| frames | {n} | {n} | {n} |"]

        def line(name, rows_, key, fmt):
            cells = [fmt % mean([key(r[m]) for _, r in rows_]) for m in METHODS]
            table.append(f"| {name} | " + " | ".join(cells) + " |")

        line("RANSAC matches to the previous frame", rows, lambda v: v[2], "%.0f")
        line(f"... in the darkest {len(dark)} frames (mean gray <= {cut:.0f})", dark, lambda v: v[2], "%.0f")
        line("keypoints per frame", rows, lambda v: v[0], "%.0f")
        enh = {m: enhance_mean(m) for m in METHODS}
        table.append("| enhancement ms per frame | " + " | ".join(
            "%.2f" % enh[m] if m != "baseline" else "-" for m in METHODS) + " |")
        line("extraction ms per frame", rows, lambda v: v[1], "%.2f")
        with open(os.path.join(self.args.output, "frames.csv"), "w", newline="") as f:
            writer = csv.writer(f)
            writer.writerow(["stamp", "frame", "mean_gray"] + [f"{m}_{k}" for m in METHODS
                                                              for k in ("keypoints", "extract_ms", "ransac_matches")])
            for stamp, r in rows:
                writer.writerow([f"{stamp.to_sec():.6f}", self.index(stamp), "%.1f" % light.get(stamp, float("nan"))]
                                + [f"{x:.3f}" if isinstance(x, float) else x for m in METHODS for x in r[m]])
        with open(os.path.join(self.args.output, "summary.md"), "w") as f:
            f.write(f"# enhanced_orb demo: {self.args.bag}\n\n" + "\n".join(table) + "\n\n")
            f.write("Annotated frames (default mode | paper preset | original ORB):\n\n")
            for path in sorted(self.saved):
                f.write(f"![{os.path.basename(path)}]({os.path.basename(path)})\n")
        print("\n\n" + "\n".join(table))
        print(f"\nwrote {self.args.output}/summary.md, frames.csv and {len(self.saved)} annotated frames")
        return n


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--output", required=True)
    parser.add_argument("--frames", type=int, default=0, help="frames in the bag, for the progress bar")
    parser.add_argument("--fps", type=float, default=20.0, help="frame rate of the bag, to number frames")
    parser.add_argument("--save", type=int, nargs="*", default=[0, 54, 109, 163], help="frame numbers to save")
    parser.add_argument("--camera", default="cam0")
    parser.add_argument("--bag", default="")
    parser.add_argument("--idle", type=float, default=5.0, help="seconds without frames that end the run")
    parser.add_argument("--wait", type=float, default=60.0, help="seconds to wait for the first frame")
    args = parser.parse_args(rospy.myargv()[1:])
    args.save = set(args.save)
    os.makedirs(args.output, exist_ok=True)

    rospy.init_node("demo_monitor")
    monitor = Monitor(args)
    start = time.monotonic()
    while not rospy.is_shutdown():
        time.sleep(0.5)
        monitor.progress()
        last = monitor.last_message
        if last is None and time.monotonic() - start > args.wait:
            print("\ndemo_monitor: no keypoints arrived; is the pipeline running?")
            sys.exit(1)
        if last is not None and time.monotonic() - last > args.idle:
            break
    sys.exit(0 if monitor.summary() > 0 else 1)


if __name__ == "__main__":
    main()
