#!/usr/bin/env python3
"""Measures the running nodelet chain (launch/pipeline.launch): the frame rate it sustains with no
frame dropped when frames come as fast as it takes them, and the latency from image stamp to
keypoints out at a fixed rate. Frames come from a bag; results go to a CSV file.

  pipeline_benchmark.py --bag FILE [--topic /cam0/image_raw] [--rate 20] [--output pipeline.csv]
                        [--stereo-topic /cam1/image_raw --stereo-camera cam1]

With a second camera (a second chain running under its namespace), also measures the pair rate
and the latency when both cameras' frames come together, as a stereo driver sends them.
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


def stereo_throughput(chains, frame_lists, window):
    """Pairs per second with at most `window` pairs in flight in each chain."""
    for chain in chains:
        with chain.lock:
            chain.received.clear()
    stamps = []
    start = time.time()
    for i, pair in enumerate(zip(*frame_lists)):
        stamp = rospy.Time(5000 + i)
        stamps.append(stamp)
        for chain, frame in zip(chains, pair):
            with chain.lock:
                while len(stamps) - 1 - len(chain.received) >= window:
                    if not chain.lock.wait(10.0):
                        sys.exit("pipeline_benchmark: no keypoints within 10 s")
            frame.header.stamp = stamp
            chain.pub.publish(frame)
    time.sleep(1.0)
    arrivals = [max(chain.received.values()) for chain in chains if chain.received]
    elapsed = (max(arrivals) - start) if arrivals else float("nan")
    dropped = sum(len([s for s in stamps if s not in chain.received]) for chain in chains)
    return len(stamps) / elapsed, dropped


def stereo_latency(chains, frame_lists, rate):
    """Stamp-to-keypoints latency [ms] of both cameras' frames, sent together at `rate` Hz."""
    for chain in chains:
        with chain.lock:
            chain.received.clear()
    sent = []
    period = 1.0 / rate
    next_time = time.time()
    for pair in zip(*frame_lists):
        now = time.time()
        if now < next_time:
            time.sleep(next_time - now)
        next_time += period
        stamp = rospy.Time.from_sec(time.time())
        for chain, frame in zip(chains, pair):
            frame.header.stamp = stamp
            chain.pub.publish(frame)
        sent.append(stamp)
    time.sleep(1.0)
    latencies, lost = [], 0
    for chain in chains:
        with chain.lock:
            for s in sent:
                if s in chain.received:
                    latencies.append((chain.received[s] - s.to_sec()) * 1000.0)
                else:
                    lost += 1
    return latencies, lost


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--bag", required=True)
    parser.add_argument("--topic", default="/cam0/image_raw")
    parser.add_argument("--camera", default="cam0")
    parser.add_argument("--rate", type=float, default=20.0)
    parser.add_argument("--window", type=int, default=4, help="frames in flight (below the nodelets' queue_size)")
    parser.add_argument("--repeat", type=int, default=3, help="passes over the bag's frames")
    parser.add_argument("--output", default="pipeline.csv")
    parser.add_argument("--stereo-topic", default="", help="the second camera's images in the bag")
    parser.add_argument("--stereo-camera", default="cam1", help="the second chain's namespace")
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
    if args.stereo_topic:
        second = [msg for _, msg, _ in rosbag.Bag(args.bag).read_messages(topics=[args.stereo_topic])]
        if not second:
            sys.exit(f"pipeline_benchmark: no messages on {args.stereo_topic} in {args.bag}")
        chains = [chain, Chain(args.stereo_camera)]
        chains[1].wait_connected()
        time.sleep(1.0)
        n = min(len(frames), len(second))
        lists = [frames[:n] * args.repeat, second[:n] * args.repeat]
        stereo_throughput(chains, [frames[:10], second[:10]], args.window)  # warm-up
        pairs, stereo_dropped = stereo_throughput(chains, lists, args.window)
        stereo, stereo_lost = stereo_latency(chains, lists, args.rate)
        s50, s99 = (np.percentile(stereo, [50, 99]) if stereo else (float("nan"),) * 2)
        rows += [
            ("stereo: max pairs per second without drops", f"{pairs:.1f}"),
            ("stereo: dropped at max rate", stereo_dropped),
            (f"stereo: latency p50 at {args.rate:g} Hz [ms]", f"{s50:.1f}"),
            (f"stereo: latency p99 at {args.rate:g} Hz [ms]", f"{s99:.1f}"),
            (f"stereo: dropped at {args.rate:g} Hz", stereo_lost),
        ]
    with open(args.output, "w", newline="") as f:
        csv.writer(f).writerows([("key", "value"), *rows])
    for key, value in rows:
        print(f"{key}: {value}")


if __name__ == "__main__":
    main()
