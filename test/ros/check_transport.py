#!/usr/bin/env python3
"""With transports that cannot be loaded, the nodelets subscribe raw images: keypoints arrive and
the nodelet manager stays alive throughout."""
import unittest

import rosnode
import rospy
import rostest

from pipeline_client import OUTPUT_S, PipelineClient, image, scene

MANAGER = "/cam0/enhanced_orb_manager"


class Transport(unittest.TestCase):
    def test_missing_transport_falls_back_to_raw(self):
        client = PipelineClient()
        self.assertTrue(client.connected(), "no frame came through the pipeline")
        for i in range(20):
            self.assertTrue(rosnode.rosnode_ping(MANAGER, max_count=1), "manager died before frame %d" % i)
            stamp = client.send(image("mono8", scene(seed=i)))
            self.assertTrue(client.processed(stamp, OUTPUT_S), "no keypoints for frame %d" % i)
        self.assertTrue(rosnode.rosnode_ping(MANAGER, max_count=1), "manager died")


if __name__ == "__main__":
    rospy.init_node("check_transport")
    rostest.rosrun("enhanced_orb", "check_transport", Transport)
