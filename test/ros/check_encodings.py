#!/usr/bin/env python3
"""Feeds the running pipeline frames of every encoding, and malformed ones. Supported encodings
give keypoints; bad frames give a warning naming the problem and no output; the good frame after
each bad one is processed."""
import threading
import unittest

import numpy as np
import rospy
import rostest
from rosgraph_msgs.msg import Log
from sensor_msgs.msg import Image

from enhanced_orb.msg import KeypointArray

W, H = 160, 120


def scene():
    rng = np.random.RandomState(3)
    gray = np.full((H, W), 100, np.uint8)
    for _ in range(40):
        x, y = rng.randint(0, W - 10), rng.randint(0, H - 10)
        gray[y:y + rng.randint(5, 30), x:x + rng.randint(5, 30)] = rng.randint(0, 256)
    return gray


def image(encoding, pixels, step=None, data=None, width=W, height=H):
    msg = Image()
    msg.encoding = encoding
    msg.width, msg.height = width, height
    raw = np.ascontiguousarray(pixels).tobytes()
    msg.step = step if step is not None else (len(raw) // height if height else 0)
    msg.data = raw if data is None else data
    return msg


GRAY = scene()
GOOD = {
    "mono8": image("mono8", GRAY),
    "8UC1": image("8UC1", GRAY),
    "mono16": image("mono16", GRAY.astype("<u2") * 257),
    "16UC1": image("16UC1", GRAY.astype("<u2") * 257),
    "bgr8": image("bgr8", np.dstack([GRAY] * 3)),
    "rgb8": image("rgb8", np.dstack([GRAY] * 3)),
    "bgra8": image("bgra8", np.dstack([GRAY] * 4)),
    "rgba8": image("rgba8", np.dstack([GRAY] * 4)),
    "bayer_rggb8": image("bayer_rggb8", GRAY),
    "yuv422": image("yuv422", np.dstack([np.full_like(GRAY, 128), GRAY])),
}
BAD = {  # name: (message, text the warning must contain)
    "32FC1": (image("32FC1", GRAY.astype(np.float32)), "32FC1"),
    "8UC3": (image("8UC3", np.dstack([GRAY] * 3)), "8UC3"),
    "short data": (image("mono8", GRAY, data=GRAY.tobytes()[: W * H // 2]), "data holds"),
    "step below a row": (image("mono8", GRAY, step=W - 1, data=GRAY.tobytes()), "step"),
    "empty": (image("mono8", np.zeros((0, 0), np.uint8), step=0, width=0, height=0), "empty"),
}


class Encodings(unittest.TestCase):
    def setUp(self):
        self.lock = threading.Lock()
        self.stamps = set()
        self.warnings = []
        self.next_stamp = 1
        rospy.Subscriber("/cam0/keypoints", KeypointArray, self.on_keypoints, queue_size=50)
        rospy.Subscriber("/rosout", Log, self.on_log, queue_size=100)
        self.pub = rospy.Publisher("/cam0/image_raw", Image, queue_size=10)
        deadline = rospy.Time.now() + rospy.Duration(30)
        while self.pub.get_num_connections() == 0 and rospy.Time.now() < deadline:
            rospy.sleep(0.1)
        self.assertGreater(self.pub.get_num_connections(), 0, "the pipeline never subscribed its input")

    def on_keypoints(self, msg):
        with self.lock:
            self.stamps.add(msg.header.stamp)

    def on_log(self, msg):
        if msg.level >= Log.WARN:
            with self.lock:
                self.warnings.append(msg.msg)

    def send(self, msg):
        msg.header.stamp = rospy.Time(self.next_stamp)
        msg.header.frame_id = "cam0"
        self.next_stamp += 1
        self.pub.publish(msg)
        return msg.header.stamp

    def wait_until(self, condition, seconds):
        deadline = rospy.Time.now() + rospy.Duration(seconds)
        while rospy.Time.now() < deadline:
            with self.lock:
                if condition():
                    return True
            rospy.sleep(0.05)
        return False

    def expect_output(self, msg, what):
        stamp = self.send(msg)
        self.assertTrue(self.wait_until(lambda: stamp in self.stamps, 10.0), "no keypoints for " + what)

    def test_supported_encodings_give_output(self):
        for name, msg in GOOD.items():
            self.expect_output(msg, name)

    def test_bad_frames_warn_and_the_next_good_frame_is_processed(self):
        for name, (msg, text) in BAD.items():
            stamp = self.send(msg)
            self.assertTrue(self.wait_until(lambda: any(text in w for w in self.warnings), 10.0),
                            "no warning containing %r for %s; warnings: %s" % (text, name, self.warnings))
            rospy.sleep(0.5)
            with self.lock:
                self.assertNotIn(stamp, self.stamps, "output for a bad frame: " + name)
            self.expect_output(GOOD["mono8"], "the good frame after " + name)


if __name__ == "__main__":
    rospy.init_node("check_encodings")
    rostest.rosrun("enhanced_orb", "check_encodings", Encodings)
