#!/usr/bin/env python3
"""Load and faults on the running pipeline (4-thread manager): FRAMES half-size EuRoC frames as fast
as the chain takes them, with resident memory compared after warm-up and at the end; a storm of
random valid reconfigurations at 50 Hz while frames flow; nodelets unloaded and reloaded while
frames flow. The manager must survive all of it and keep working."""
import argparse
import ast
import random
import signal
import subprocess
import threading
import time
import unittest
import xmlrpc.client

import cv2
import dynamic_reconfigure.client
import numpy as np
import rosbag
import rosgraph
import rosnode
import rospy
import rostest
from sensor_msgs.msg import Image

from enhanced_orb.msg import KeypointArray

# How long the feeder waits for a frame in flight before counting it lost: long enough that a
# loaded machine alone cannot lose one (a frame takes milliseconds).
PATIENCE_S = 60.0
MANAGER = "/cam0/enhanced_orb_manager"
ARGS = None


def half_size_frames(bag, topic="/cam0/image_raw"):
    frames = []
    for _, msg, _ in rosbag.Bag(bag).read_messages(topics=[topic]):
        gray = np.frombuffer(msg.data, np.uint8).reshape(msg.height, msg.step)[:, :msg.width]
        small = cv2.resize(gray, (msg.width // 2, msg.height // 2), interpolation=cv2.INTER_AREA)
        out = Image(encoding="mono8", height=small.shape[0], width=small.shape[1], step=small.shape[1],
                    data=small.tobytes())
        out.header.frame_id = "cam0"
        frames.append(out)
    return frames


def manager_rss_kb():
    uri = rosnode.get_api_uri(rosgraph.Master("/check_load"), MANAGER)
    _, _, pid = xmlrpc.client.ServerProxy(uri).getPid("/check_load")
    with open(f"/proc/{pid}/status") as f:
        for line in f:
            if line.startswith("VmRSS:"):
                return int(line.split()[1])
    raise RuntimeError("no VmRSS")


class Load(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.frames = half_size_frames(ARGS.bag)
        cls.lock = threading.Condition()
        cls.processed = 0
        cls.pub = rospy.Publisher("/cam0/image_raw", Image, queue_size=20)
        rospy.Subscriber("/cam0/keypoints", KeypointArray, cls.on_keypoints, queue_size=100)
        deadline = time.time() + 30
        while cls.pub.get_num_connections() == 0 and time.time() < deadline:
            time.sleep(0.05)

    @classmethod
    def on_keypoints(cls, msg):
        with cls.lock:
            cls.processed += 1
            cls.lock.notify_all()

    def stream(self, count, window=4, stop=None):
        """Sends `count` frames (or until `stop` is set) with at most `window` in flight."""
        with self.lock:
            start = self.processed
        sent = 0
        while sent < count and not rospy.is_shutdown() and not (stop and stop.is_set()):
            with self.lock:
                while sent - (self.processed - start) >= window:
                    if not self.lock.wait(PATIENCE_S):
                        return sent, self.processed - start
            msg = self.frames[sent % len(self.frames)]
            msg.header.stamp = rospy.Time(1, 0) + rospy.Duration(0, 1000 * (sent + 1))
            self.pub.publish(msg)
            sent += 1
        deadline = time.time() + PATIENCE_S
        with self.lock:
            while self.processed - start < sent and time.time() < deadline:
                self.lock.wait(1.0)
            return sent, self.processed - start

    def assert_alive(self, after):
        self.assertTrue(rosnode.rosnode_ping(MANAGER, max_count=1), "the manager died after " + after)
        sent, done = self.stream(5)
        self.assertEqual(done, sent, "frames lost after " + after)

    def test_1_many_frames_memory_stays_flat(self):
        self.assertGreater(self.pub.get_num_connections(), 0, "the pipeline never subscribed its input")
        warm = min(1000, ARGS.frames // 10)
        sent, done = self.stream(warm)
        self.assertEqual(done, sent)
        rss_warm = manager_rss_kb()
        start = time.time()
        sent, done = self.stream(ARGS.frames - warm)
        elapsed = time.time() - start
        rss_end = manager_rss_kb()
        rospy.loginfo(f"load: {sent} frames in {elapsed:.1f} s ({sent / elapsed:.0f} fps), {done} processed; "
                      f"manager RSS {rss_warm} kB after warm-up, {rss_end} kB at the end")
        self.assertEqual(done, sent, "frames lost under load")
        self.assertLess(rss_end - rss_warm, 5 * 1024, "resident memory grew by more than 5 MB")
        self.assert_alive("the load")

    def test_2_reconfigure_storm(self):
        clients = {n: dynamic_reconfigure.client.Client(n, timeout=30) for n in ("/cam0/enhance", "/cam0/extract")}
        limits = {n: {p["name"]: p for p in c.get_parameter_descriptions()} for n, c in clients.items()}
        defaults = {n: dict(c.get_configuration(timeout=10)) for n, c in clients.items()}
        rng = random.Random(7)
        stop = threading.Event()
        feeder = threading.Thread(target=lambda: self.stream(10 ** 9, stop=stop))
        feeder.start()
        start = time.time()
        updates = 500
        for k in range(updates):
            node = rng.choice(list(clients))
            values = {}
            for name, p in limits[node].items():
                if p["type"] == "int":
                    values[name] = rng.randint(int(p["min"]), min(int(p["max"]), 2000))
                elif p["type"] == "double":
                    values[name] = rng.uniform(float(p["min"]), float(p["max"]))
                elif p["type"] == "bool":
                    values[name] = rng.random() < 0.5
                elif p["type"] == "str":
                    options = [c["value"] for c in ast.literal_eval(p["edit_method"])["enum"]] if p["edit_method"] else [""]
                    values[name] = rng.choice(options)
            clients[node].update_configuration(values)
            time.sleep(max(0.0, start + (k + 1) / 50.0 - time.time()))  # paced at 50 per second
        stop.set()
        feeder.join(30)
        rospy.loginfo(f"storm: {updates} reconfigurations in {time.time() - start:.1f} s")
        for node, c in clients.items():
            c.update_configuration(defaults[node])
        self.assert_alive("the reconfigure storm")

    def test_3_unload_and_reload_while_frames_flow(self):
        stop = threading.Event()
        feeder = threading.Thread(target=lambda: self.stream(10 ** 9, stop=stop))
        feeder.start()
        extra = []
        got = threading.Event()
        rospy.Subscriber("/cam0/extra/keypoints", KeypointArray, lambda m: got.set(), queue_size=5)
        for cycle in range(5):
            got.clear()
            loaders = [
                subprocess.Popen(["rosrun", "nodelet", "nodelet", "load", "enhanced_orb/EnhanceNodelet", MANAGER,
                                  "__name:=extra_enhance", "__ns:=/cam0", "image:=image_raw",
                                  "image_enhanced:=extra/image_enhanced"]),
                subprocess.Popen(["rosrun", "nodelet", "nodelet", "load", "enhanced_orb/ExtractNodelet", MANAGER,
                                  "__name:=extra_extract", "__ns:=/cam0", "image:=extra/image_enhanced",
                                  "keypoints:=extra/keypoints", "image_annotated:=extra/image_annotated"]),
            ]
            extra.extend(loaders)
            self.assertTrue(got.wait(30.0), "the reloaded nodelets produced nothing (cycle %d)" % cycle)
            for p in reversed(loaders):  # unloads the nodelet while frames flow
                p.send_signal(signal.SIGINT)
            for p in loaders:
                p.wait(30)
        stop.set()
        feeder.join(30)
        self.assert_alive("unloading and reloading")


if __name__ == "__main__":
    parser = argparse.ArgumentParser()
    parser.add_argument("--bag", required=True)
    parser.add_argument("--frames", type=int, default=10000)
    ARGS, _ = parser.parse_known_args(rospy.myargv()[1:])
    rospy.init_node("check_load")
    rostest.rosrun("enhanced_orb", "check_load", Load)
