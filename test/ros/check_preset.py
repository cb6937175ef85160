#!/usr/bin/env python3
"""The nodelets started with preset:=stretch (config/stretch.yaml) run the stretch preset: the
parameters it sets differ from the default mode's, the others keep the default mode's, and a frame
is enhanced by the stretch curve. With ~preset baseline (preset:=baseline, config/baseline.yaml):
the enhancement is off and the extractor runs one fixed threshold of 20."""
import threading
import unittest

import dynamic_reconfigure.client
import numpy as np
import rospy
import rostest

from enhanced_orb.msg import EnhanceStatus
from pipeline_client import PipelineClient, image, scene

# What each preset sets (include/enhanced_orb/params.h), and what it keeps of the default mode or the
# parameter file (cfg/*.cfg defaults, config/<preset>.yaml).
EXPECTED = {
    "stretch": {"/cam0/enhance": {"tone_curve": "stretch", "tau": 0.05, "enhance": True, "alpha": 0.5, "beta": 1.0,
                                  "gamma_mode": "always"},
                "/cam0/extract": {"candidate_ratio": 1.0, "max_features": 1000}},
    "baseline": {"/cam0/enhance": {"enhance": False},
                 "/cam0/extract": {"threshold_mode": "fixed", "fast_threshold": 20, "max_features": 1000}},
}


class Preset(unittest.TestCase):
    def configuration(self, node):
        return dynamic_reconfigure.client.Client(node, timeout=30).get_configuration(timeout=30)

    def test_live_configuration_is_the_presets(self):
        for node, expected in EXPECTED[PRESET_NAME].items():
            config = self.configuration(node)
            for name, value in expected.items():
                self.assertEqual(config[name], value, "%s: %s = %s, expected %s" % (node, name, config[name], value))

    def test_a_frame_is_enhanced_as_the_preset_says(self):
        lock = threading.Lock()
        statuses = []

        def on_status(msg):
            with lock:
                statuses.append(msg)

        rospy.Subscriber("/cam0/enhance_status", EnhanceStatus, on_status, queue_size=10)
        client = PipelineClient()
        self.assertTrue(client.connected(), "no frame came through the pipeline")
        with lock:
            statuses.clear()  # those of the frames that connected the chain
        dark = (scene() // 4).astype("uint8")
        # With the enhancement off a mono8 frame is handed on as it is, without a status; a colour
        # frame is converted, and its status says that no tone curve ran.
        frame = image("mono8", dark) if PRESET_NAME == "stretch" else image("bgr8", np.dstack([dark] * 3))
        for _ in range(50):  # until the status subscription is connected too
            stamp = client.send(frame)
            if client.processed(stamp, 1.0):
                with lock:
                    if statuses:
                        break
        with lock:
            self.assertTrue(statuses, "no enhance_status received")
            if PRESET_NAME == "stretch":
                self.assertEqual(statuses[-1].tone_curve, "stretch")
                self.assertTrue(statuses[-1].poor_quality, "the curve did not run (gamma_mode always)")
            else:  # the enhancement is off: no tone curve ran
                self.assertEqual(statuses[-1].gamma_mode, "never")
                self.assertFalse(statuses[-1].poor_quality, "a tone curve ran with the enhancement off")


if __name__ == "__main__":
    rospy.init_node("check_preset")
    PRESET_NAME = rospy.get_param("~preset", "stretch")
    rostest.rosrun("enhanced_orb", "preset" if PRESET_NAME == "stretch" else "preset_" + PRESET_NAME, Preset)
