#!/usr/bin/env python3
"""The nodelets subscribe their inputs only while someone listens to one of their outputs."""
import unittest

import rosgraph
import rospy
import rostest
from sensor_msgs.msg import Image

from enhanced_orb.msg import KeypointArray

MANAGER = "/cam0/enhanced_orb_manager"


def subscribed(topic):
    """Whether the nodelet manager subscribes `topic`, by the master's record."""
    _, subscribers, _ = rosgraph.Master("/check_lazy").getSystemState()
    return any(name == topic and MANAGER in nodes for name, nodes in subscribers)


class Lazy(unittest.TestCase):
    def wait_until(self, condition, what, seconds=30.0):
        deadline = rospy.Time.now() + rospy.Duration(seconds)
        while rospy.Time.now() < deadline:
            if condition():
                return
            rospy.sleep(0.1)
        self.fail("timed out waiting until " + what)

    def setUp(self):
        for node in ("/cam0/enhance", "/cam0/extract", "/cam0/baseline_extract"):
            rospy.wait_for_service(node + "/set_parameters", timeout=30)
        rospy.sleep(1.0)

    def test_inputs_follow_the_outputs_subscribers(self):
        self.assertFalse(subscribed("/cam0/image_raw"), "image_raw subscribed with nobody listening")
        self.assertFalse(subscribed("/cam0/image_enhanced"), "image_enhanced subscribed with nobody listening")

        sub = rospy.Subscriber("/cam0/keypoints", KeypointArray, lambda m: None)
        self.wait_until(lambda: subscribed("/cam0/image_enhanced"), "the extractor subscribes image_enhanced")
        self.wait_until(lambda: subscribed("/cam0/image_raw"), "the enhancer subscribes image_raw")
        sub.unregister()
        self.wait_until(lambda: not subscribed("/cam0/image_enhanced"), "the extractor unsubscribes")
        self.wait_until(lambda: not subscribed("/cam0/image_raw"), "the enhancer unsubscribes")

        # The baseline reads image_raw directly; its annotated image alone is enough to wake it.
        sub = rospy.Subscriber("/cam0/baseline/image_annotated", Image, lambda m: None)
        self.wait_until(lambda: subscribed("/cam0/image_raw"), "the baseline subscribes image_raw")
        self.assertFalse(subscribed("/cam0/image_enhanced"))
        sub.unregister()
        self.wait_until(lambda: not subscribed("/cam0/image_raw"), "the baseline unsubscribes")


if __name__ == "__main__":
    rospy.init_node("check_lazy")
    rostest.rosrun("enhanced_orb", "check_lazy", Lazy)
