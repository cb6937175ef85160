#!/usr/bin/env python3
"""Watches the enhanced ORB pipeline and its baseline while a bag plays: prints progress, then a
summary table; writes the summary (Markdown and per-frame CSV) and a few annotated frames, the
improved and the baseline side by side, to an output folder. Exits when the frames stop coming."""
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


class Monitor:
    def __init__(self, args):
        self.args = args
        self.lock = threading.Lock()
        self.bridge = CvBridge()
        self.rows = {}  # stamp -> {"improved": (n, ms), "baseline": (n, ms)}
        self.annotated = {"improved": {}, "baseline": {}}  # stamp -> image, for the frames to save
        self.enhance_ms = []  # (frames, mean ms) per diagnostics window
        self.first_stamp = None
        self.last_message = None
        self.saved = []
        self.shown = -1  # frames done at the last progress line
        cam = args.camera
        rospy.Subscriber(f"/{cam}/keypoints", KeypointArray, self.on_keypoints, "improved", queue_size=50)
        rospy.Subscriber(f"/{cam}/baseline/keypoints", KeypointArray, self.on_keypoints, "baseline", queue_size=50)
        rospy.Subscriber(f"/{cam}/image_annotated", Image, self.on_annotated, "improved", queue_size=5,
                         buff_size=2 ** 24)
        rospy.Subscriber(f"/{cam}/baseline/image_annotated", Image, self.on_annotated, "baseline", queue_size=5,
                         buff_size=2 ** 24)
        rospy.Subscriber("/diagnostics", DiagnosticArray, self.on_diagnostics, queue_size=10)

    def index(self, stamp):
        if self.first_stamp is None:
            self.first_stamp = stamp
        return int(round((stamp - self.first_stamp).to_sec() * self.args.fps))

    def on_keypoints(self, msg, which):
        with self.lock:
            self.index(msg.header.stamp)
            self.rows.setdefault(msg.header.stamp, {})[which] = (len(msg.keypoints), msg.extract_ms)
            self.last_message = time.monotonic()

    def on_annotated(self, msg, which):
        with self.lock:
            if self.index(msg.header.stamp) not in self.args.save:
                return
            self.annotated[which][msg.header.stamp] = self.bridge.imgmsg_to_cv2(msg, "bgr8")
            self.save_pairs()

    def on_diagnostics(self, msg):
        for status in msg.status:
            # diagnostic_updater names a status "<node name without the leading slash>: <task>".
            if status.name.endswith(f"{self.args.camera}/enhance: processing"):
                values = {kv.key: kv.value for kv in status.values}
                frames = float(values.get("frames per second", 0))
                if frames > 0:
                    with self.lock:
                        self.enhance_ms.append((frames, float(values["mean processing time [ms]"])))

    def save_pairs(self):
        for stamp in set(self.annotated["improved"]) & set(self.annotated["baseline"]):
            improved = self.annotated["improved"].pop(stamp)
            baseline = self.annotated["baseline"].pop(stamp)
            index = self.index(stamp)
            pair = np.hstack([improved, np.zeros((improved.shape[0], 8, 3), np.uint8), baseline])
            for text, x in (("enhanced ORB", 10), ("original ORB", improved.shape[1] + 18)):
                cv2.putText(pair, text, (x, improved.shape[0] - 12), cv2.FONT_HERSHEY_SIMPLEX, 0.7, (0, 0, 0), 4,
                            cv2.LINE_AA)
                cv2.putText(pair, text, (x, improved.shape[0] - 12), cv2.FONT_HERSHEY_SIMPLEX, 0.7, (255, 255, 255),
                            1, cv2.LINE_AA)
            path = os.path.join(self.args.output, f"frame_{index:04d}.png")
            cv2.imwrite(path, pair)
            self.saved.append(path)

    def progress(self):
        with self.lock:
            done = [r for r in self.rows.values() if len(r) == 2]
        if len(done) == self.shown:
            return
        tty = sys.stdout.isatty()
        if not tty and len(done) - self.shown < 25 and len(done) < self.args.frames:
            return  # in a log, a line every 25 frames
        self.shown = len(done)
        total = self.args.frames
        width = 30
        filled = int(width * min(len(done), total) / total) if total else 0
        last = done[-1] if done else None
        text = f"\r[{'#' * filled}{'.' * (width - filled)}] {len(done):4d}/{total} frames"
        if last:
            text += f"  keypoints: enhanced {last['improved'][0]:6d}  original {last['baseline'][0]:6d}"
        sys.stdout.write(text if tty else text[1:] + "\n")
        sys.stdout.flush()

    def summary(self):
        with self.lock:
            rows = sorted((s, r) for s, r in self.rows.items() if len(r) == 2)
            enhance = list(self.enhance_ms)
        n = len(rows)

        def mean(values):
            return sum(values) / len(values) if values else float("nan")

        imp_kp = mean([r["improved"][0] for _, r in rows])
        base_kp = mean([r["baseline"][0] for _, r in rows])
        imp_ms = mean([r["improved"][1] for _, r in rows])
        base_ms = mean([r["baseline"][1] for _, r in rows])
        frames = sum(f for f, _ in enhance)
        enh_ms = sum(f * m for f, m in enhance) / frames if frames else float("nan")
        table = [
            "| | original ORB (baseline) | enhanced ORB |",
            "| --- | ---: | ---: |",
            f"| frames | {n} | {n} |",
            f"| mean keypoints per frame | {base_kp:.0f} | {imp_kp:.0f} ({imp_kp / base_kp:.2f}x) |"
            if base_kp else f"| mean keypoints per frame | {base_kp:.0f} | {imp_kp:.0f} |",
            f"| mean enhancement ms per frame | - | {enh_ms:.2f} |",
            f"| mean extraction ms per frame | {base_ms:.2f} | {imp_ms:.2f} |",
            f"| mean total ms per frame | {base_ms:.2f} | {enh_ms + imp_ms:.2f} |",
        ]
        with open(os.path.join(self.args.output, "frames.csv"), "w", newline="") as f:
            writer = csv.writer(f)
            writer.writerow(["stamp", "frame", "baseline_keypoints", "improved_keypoints", "baseline_extract_ms",
                             "improved_extract_ms"])
            for stamp, r in rows:
                writer.writerow([f"{stamp.to_sec():.6f}", self.index(stamp), r["baseline"][0], r["improved"][0],
                                 f"{r['baseline'][1]:.3f}", f"{r['improved'][1]:.3f}"])
        with open(os.path.join(self.args.output, "summary.md"), "w") as f:
            f.write(f"# enhanced_orb demo: {self.args.bag}\n\n" + "\n".join(table) + "\n\n")
            f.write("Annotated frames (enhanced left, original right):\n\n")
            for path in sorted(self.saved):
                f.write(f"![{os.path.basename(path)}]({os.path.basename(path)})\n")
        print("\n\n" + "\n".join(table))
        print(f"\nwrote {self.args.output}/summary.md, frames.csv and {len(self.saved)} annotated frames")
        return n


def main():
    parser = argparse.ArgumentParser(description=__doc__)
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
