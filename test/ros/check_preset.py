#!/usr/bin/env python3
"""The nodelets started with preset:=stretch (config/stretch.yaml) run the stretch preset: the
parameters it sets differ from the default mode's, the others keep the default mode's, and a frame
is enhanced by the stretch curve."""
import threading
import unittest

import dynamic_reconfigure.client
import rospy
import rostest

from enhanced_orb.msg import EnhanceStatus
from pipeline_client import PipelineClient, image, scene

# Params::stretch(): the default mode with these three (include/enhanced_orb/params.h).
PRESET = {"/cam0/enhance": {"tone_curve": "stretch", "tau": 0.05}, "/cam0/extract": {"candidate_ratio": 1.0}}
# And what it keeps of the default mode (cfg/*.cfg defaults).
KEPT = {"/cam0/enhance": {"alpha": 0.5, "beta": 1.0, "gamma_mode": "always"},
        "/cam0/extract": {"max_features": 1000}}


class Preset(unittest.TestCase):
    def configuration(self, node):
        return dynamic_reconfigure.client.Client(node, timeout=30).get_configuration(timeout=30)

    def test_live_configuration_is_the_presets(self):
        for values in (PRESET, KEPT):
            for node, expected in values.items():
                config = self.configuration(node)
                for name, value in expected.items():
                    self.assertEqual(config[name], value,
                                     "%s: %s = %s, expected %s" % (node, name, config[name], value))

    def test_a_frame_is_enhanced_by_the_stretch_curve(self):
        lock = threading.Lock()
        statuses = []

        def on_status(msg):
            with lock:
                statuses.append(msg)

        rospy.Subscriber("/cam0/enhance_status", EnhanceStatus, on_status, queue_size=10)
        client = PipelineClient()
        self.assertTrue(client.connected(), "the pipeline did not subscribe its input")
        dark = (scene() // 4).astype("uint8")
        for _ in range(50):  # until the status subscription is connected too
            stamp = client.send(image("mono8", dark))
            if client.processed(stamp, 1.0):
                with lock:
                    if statuses:
                        break
        with lock:
            self.assertTrue(statuses, "no enhance_status received")
            self.assertEqual(statuses[-1].tone_curve, "stretch")
            self.assertTrue(statuses[-1].poor_quality, "the curve did not run (gamma_mode always)")


if __name__ == "__main__":
    rospy.init_node("check_preset")
    rostest.rosrun("enhanced_orb", "preset", Preset)
