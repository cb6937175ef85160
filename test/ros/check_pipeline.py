#!/usr/bin/env python3
"""Every KeypointArray and annotated image of the running pipeline is consistent with the image it
came from."""
import collections
import unittest

import rospy
import rostest
from sensor_msgs.msg import Image

from enhanced_orb.msg import EnhanceStatus, KeypointArray

MESSAGES = 40  # per output
BUDGET = 1000  # max_features of config/default.yaml
OUTPUTS = ("/cam0/keypoints", "/cam0/baseline/keypoints", "/cam0/paper/keypoints")
ANNOTATED = "/cam0/image_annotated"


class PipelineConsistency(unittest.TestCase):
    def setUp(self):
        self.images = {}  # stamp -> (width, height)
        self.outputs = collections.defaultdict(list)
        rospy.Subscriber("/cam0/image_raw", Image, self.on_image, queue_size=50)
        for name in OUTPUTS:
            rospy.Subscriber(name, KeypointArray, self.on_keypoints, callback_args=name, queue_size=50)
        self.annotated = []
        rospy.Subscriber(ANNOTATED, Image, self.annotated.append, queue_size=50)
        self.statuses = []
        rospy.Subscriber("/cam0/enhance_status", EnhanceStatus, self.statuses.append, queue_size=50)

    def on_image(self, msg):
        self.images[msg.header.stamp] = (msg.width, msg.height)

    def on_keypoints(self, msg, name):
        self.outputs[name].append(msg)

    def wait_for_messages(self):
        deadline = rospy.Time.now() + rospy.Duration(60)
        while not rospy.is_shutdown() and rospy.Time.now() < deadline:
            if all(len(self.outputs[n]) >= MESSAGES for n in OUTPUTS) and len(self.annotated) >= MESSAGES:
                return
            rospy.sleep(0.1)
        self.fail("too few messages: %s, %d on %s" % ({n: len(m) for n, m in self.outputs.items()},
                                                       len(self.annotated), ANNOTATED))

    def check_common(self, msg):
        self.assertIn(msg.header.stamp, self.images, "stamp %s is no input image's" % msg.header.stamp)
        self.assertEqual(msg.header.frame_id, "cam0")
        self.assertEqual((msg.width, msg.height), self.images[msg.header.stamp])
        self.assertEqual(msg.descriptor_bytes, 32)
        self.assertEqual(len(msg.descriptors), 32 * len(msg.keypoints))
        self.assertEqual(msg.grid_size, 5)
        self.assertEqual(len(msg.cell_thresholds), 25)
        self.assertEqual(msg.n_levels, 8)
        for kp in msg.keypoints:
            self.assertTrue(0 <= kp.x < msg.width and 0 <= kp.y < msg.height, "keypoint outside the image")
            self.assertTrue(0 <= kp.octave < msg.n_levels)
            self.assertTrue(0.0 <= kp.angle < 360.0)

    def test_every_message_is_consistent(self):
        self.wait_for_messages()
        # The messages so far (more keep coming while the bag loops); their input images come to
        # this node on a topic of their own: wait for those.
        outputs = {name: list(msgs) for name, msgs in self.outputs.items()}
        annotated = list(self.annotated)
        deadline = rospy.Time.now() + rospy.Duration(60)
        while not rospy.is_shutdown() and rospy.Time.now() < deadline:
            unseen = [m.header.stamp for msgs in list(outputs.values()) + [annotated] for m in msgs
                      if m.header.stamp not in self.images]
            if not unseen:
                break
            rospy.sleep(0.1)
        improved = {m.header.stamp: m for m in outputs["/cam0/keypoints"]}
        baseline = {m.header.stamp: m for m in outputs["/cam0/baseline/keypoints"]}
        paper = {m.header.stamp: m for m in outputs["/cam0/paper/keypoints"]}
        for msg in list(improved.values()) + list(paper.values()):
            self.check_common(msg)
            self.assertEqual(msg.threshold_mode, "adaptive")
            self.assertTrue(all(t >= 7 for t in msg.cell_thresholds), msg.cell_thresholds)
            self.assertGreater(len(msg.keypoints), 0)
            self.assertLessEqual(len(msg.keypoints), BUDGET)
        # The excerpt's camera is static: the default mode judges it still (camera_motion auto).
        self.assertFalse(any(m.camera_moving for m in improved.values()), "a static camera judged moving")
        # The enhancement judges it too: each frame gets the still camera's gamma_mode.
        statuses = list(self.statuses)
        self.assertGreater(len(statuses), 10)
        self.assertFalse(any(s.camera_moving for s in statuses), "the enhancement judged a static camera moving")
        self.assertEqual({s.gamma_mode for s in statuses}, {"always"})
        for msg in baseline.values():
            self.check_common(msg)
            self.assertEqual(msg.threshold_mode, "fixed")
            self.assertTrue(all(t == 20 for t in msg.cell_thresholds), msg.cell_thresholds)
            self.assertLessEqual(len(msg.keypoints), BUDGET)
        for msg in annotated:
            self.assertIn(msg.header.stamp, self.images, "annotated image of no input image")
            self.assertEqual((msg.width, msg.height), self.images[msg.header.stamp])
            self.assertEqual(msg.encoding, "bgr8")
            self.assertEqual(len(msg.data), msg.step * msg.height)
        common = set(improved) & set(baseline)
        self.assertGreater(len(common), 10)
        for stamp in common:
            # EuRoC frames have corners enough: the default mode fills its budget, the original ORB
            # with its fixed threshold (at the same budget) finds no more.
            self.assertEqual(len(improved[stamp].keypoints), BUDGET)
            self.assertLessEqual(len(baseline[stamp].keypoints), len(improved[stamp].keypoints))


if __name__ == "__main__":
    rospy.init_node("check_pipeline")
    rostest.rosrun("enhanced_orb", "check_pipeline", PipelineConsistency)
