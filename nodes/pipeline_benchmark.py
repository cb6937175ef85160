#!/usr/bin/env python3
"""Measures the running nodelet chain (launch/pipeline.launch): the frame rate it sustains with no
frame dropped when frames come as fast as it takes them, and the latency from image stamp to
keypoints out at a fixed rate. Frames come from a bag; results go to a CSV file.

  pipeline_benchmark.py --bag FILE [--topic /cam0/image_raw] [--rate 20] [--output pipeline.csv]
"""
import argparse
import csv
import sys
import threading
import time

import numpy as np
import rosbag
import rospy
from sensor_msgs.msg import Image

from enhanced_orb.msg import KeypointArray


class Chain:
    def __init__(self, camera):
        self.lock = threading.Condition()
        self.received = {}  # stamp -> wall time of arrival
        self.pub = rospy.Publisher(f"/{camera}/image_raw", Image, queue_size=100)
        rospy.Subscriber(f"/{camera}/keypoints", KeypointArray, self.on_keypoints, queue_size=100)

    def on_keypoints(self, msg):
        with self.lock:
            self.received[msg.header.stamp] = time.time()
            self.lock.notify_all()

    def wait_connected(self, timeout=30.0):
        end = time.time() + timeout
        while self.pub.get_num_connections() == 0 and time.time() < end:
            time.sleep(0.05)
        if self.pub.get_num_connections() == 0:
            sys.exit("pipeline_benchmark: the pipeline never subscribed its input")

    def throughput(self, frames, window):
        """Frames per second with at most `window` frames in flight: none can be dropped."""
        with self.lock:
            self.received.clear()
        stamps = []
        start = time.time()
        for i, frame in enumerate(frames):
            frame.header.stamp = rospy.Time(1000 + i)
            stamps.append(frame.header.stamp)
            with self.lock:
                while len(stamps) - len(self.received) >= window:
                    if not self.lock.wait(10.0):
                        sys.exit("pipeline_benchmark: no keypoints within 10 s")
            self.pub.publish(frame)
        with self.lock:
            while len(self.received) < len(stamps):
                if not self.lock.wait(10.0):
                    break
        elapsed = max(self.received.values()) - start if self.received else float("nan")
        dropped = len([s for s in stamps if s not in self.received])
        return len(stamps) / elapsed, dropped

    def latency(self, frames, rate):
        """Stamp-to-keypoints latency [ms] of frames published at `rate` Hz, stamped when sent."""
        with self.lock:
            self.received.clear()
        sent = {}
        period = 1.0 / rate
        next_time = time.time()
        for frame in frames:
            now = time.time()
            if now < next_time:
                time.sleep(next_time - now)
            next_time += period
            stamp = rospy.Time.from_sec(time.time())
            frame.header.stamp = stamp
            sent[stamp] = stamp.to_sec()
            self.pub.publish(frame)
        time.sleep(1.0)
        with self.lock:
            latencies = [(self.received[s] - t) * 1000.0 for s, t in sent.items() if s in self.received]
        return latencies, len(sent) - len(latencies)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--bag", required=True)
    parser.add_argument("--topic", default="/cam0/image_raw")
    parser.add_argument("--camera", default="cam0")
    parser.add_argument("--rate", type=float, default=20.0)
    parser.add_argument("--window", type=int, default=4, help="frames in flight (below the nodelets' queue_size)")
    parser.add_argument("--repeat", type=int, default=3, help="passes over the bag's frames")
    parser.add_argument("--output", default="pipeline.csv")
    args = parser.parse_args(rospy.myargv()[1:])

    frames = [msg for _, msg, _ in rosbag.Bag(args.bag).read_messages(topics=[args.topic])]
    if not frames:
        sys.exit(f"pipeline_benchmark: no messages on {args.topic} in {args.bag}")
    rospy.init_node("pipeline_benchmark")
    chain = Chain(args.camera)
    chain.wait_connected()
    time.sleep(1.0)
    chain.throughput(frames[:10], args.window)  # warm-up
    fps, dropped = chain.throughput(frames * args.repeat, args.window)
    latencies, lost = chain.latency(frames * args.repeat, args.rate)
    p50, p99 = (np.percentile(latencies, [50, 99]) if latencies else (float("nan"),) * 2)
    rows = [
        ("frames", len(frames) * args.repeat),
        ("max fps without drops", f"{fps:.1f}"),
        ("dropped at max fps", dropped),
        (f"latency p50 at {args.rate:g} Hz [ms]", f"{p50:.1f}"),
        (f"latency p99 at {args.rate:g} Hz [ms]", f"{p99:.1f}"),
        (f"dropped at {args.rate:g} Hz", lost),
    ]
    with open(args.output, "w", newline="") as f:
        csv.writer(f).writerows([("key", "value"), *rows])
    for key, value in rows:
        print(f"{key}: {value}")


if __name__ == "__main__":
    main()
