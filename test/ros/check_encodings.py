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

from pipeline_client import H, OUTPUT_S, W, PipelineClient, image, scene

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
        self.client = PipelineClient()
        self.warnings = []
        self.lock = threading.Lock()
        rospy.Subscriber("/rosout", Log, self.on_log, queue_size=100)
        self.assertTrue(self.client.connected(), "no frame came through the pipeline")

    def on_log(self, msg):
        if msg.level >= Log.WARN:
            with self.lock:
                self.warnings.append(msg.msg)

    def warned(self, text, seconds):
        deadline = rospy.Time.now() + rospy.Duration(seconds)
        while rospy.Time.now() < deadline:
            with self.lock:
                if any(text in w for w in self.warnings):
                    return True
            rospy.sleep(0.05)
        return False

    def expect_output(self, msg, what):
        stamp = self.client.send(msg)
        self.assertTrue(self.client.processed(stamp, OUTPUT_S), "no keypoints for " + what)

    def test_supported_encodings_give_output(self):
        for name, msg in GOOD.items():
            self.expect_output(msg, name)

    def test_bad_frames_warn_and_the_next_good_frame_is_processed(self):
        for name, (msg, text) in BAD.items():
            stamp = self.client.send(msg)
            self.assertTrue(self.warned(text, OUTPUT_S),
                            "no warning containing %r for %s; warnings: %s" % (text, name, self.warnings))
            self.assertFalse(self.client.processed(stamp, 0.5), "output for a bad frame: " + name)
            self.expect_output(GOOD["mono8"], "the good frame after " + name)


if __name__ == "__main__":
    rospy.init_node("check_encodings")
    rostest.rosrun("enhanced_orb", "check_encodings", Encodings)
