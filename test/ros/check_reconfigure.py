#!/usr/bin/env python3
"""Reconfiguring the running nodelets changes their output: c_min on the extractor, beta on the
enhancer. The bag loops, so the same frames (same stamps) are seen under both settings."""
import hashlib
import threading
import unittest

import dynamic_reconfigure.client
import rospy
import rostest
from sensor_msgs.msg import Image

from enhanced_orb.msg import KeypointArray

SETTLE_S = 1.0   # frames queued before a change may still use the old values
# more than two loops of the 4.75 s bag: the latest message of each stamp is kept, so one that used
# the old values (queued before the change, however late it comes under load) is replaced by that
# stamp's next loop
COLLECT_S = 10.0


class Collector:
    """Keeps the latest message per stamp of one topic, from `start()` on."""

    def __init__(self, topic, msg_type, key):
        self.lock = threading.Lock()
        self.key = key
        self.items = None
        rospy.Subscriber(topic, msg_type, self.on_message, queue_size=50)

    def on_message(self, msg):
        with self.lock:
            if self.items is not None:
                self.items[msg.header.stamp] = self.key(msg)

    def collect(self):
        with self.lock:
            self.items = {}
        rospy.sleep(COLLECT_S)
        with self.lock:
            items, self.items = self.items, None
        return items


class Reconfigure(unittest.TestCase):
    def setUp(self):
        self.keypoints = Collector("/cam0/keypoints", KeypointArray,
                                   lambda m: (len(m.keypoints), list(m.cell_thresholds)))
        self.enhanced = Collector("/cam0/image_enhanced", Image, lambda m: hashlib.sha1(m.data).hexdigest())

    def apply(self, node, values):
        client = dynamic_reconfigure.client.Client(node, timeout=30)
        config = client.update_configuration(values)
        for name, value in values.items():
            self.assertEqual(config[name], value, "%s did not take %s = %s" % (node, name, value))
        rospy.sleep(SETTLE_S)

    def test_raising_c_min_lowers_the_count_and_lifts_every_threshold(self):
        self.apply("/cam0/extract", {"c_min": 7, "max_features": 0})  # every corner: c_min sets the count
        low = self.keypoints.collect()
        self.apply("/cam0/extract", {"c_min": 40})
        high = self.keypoints.collect()
        self.assertTrue(all(min(t) >= 40 for _, t in high.values()), "a threshold below 40 after c_min = 40")
        self.assertTrue(any(min(t) < 40 for _, t in low.values()), "c_min = 7 should leave thresholds below 40")
        common = set(low) & set(high)
        self.assertGreater(len(common), 20)
        for stamp in common:
            self.assertLess(high[stamp][0], low[stamp][0], "frame %s: %d keypoints at c_min 40, %d at 7"
                            % (stamp, high[stamp][0], low[stamp][0]))

    def test_a_refused_value_is_reported_back_and_blocks_nothing(self):
        client = dynamic_reconfigure.client.Client("/cam0/extract", timeout=30)
        before = client.update_configuration({"threshold_mode": "adaptive", "c_min": 7})
        config = client.update_configuration({"threshold_mode": "bogus"})
        self.assertEqual(config["threshold_mode"], before["threshold_mode"],
                         "the server reports a refused threshold_mode")
        config = client.update_configuration({"c_min": 40})
        self.assertEqual(config["c_min"], 40)
        self.assertEqual(config["threshold_mode"], "adaptive")
        rospy.sleep(SETTLE_S)
        after = self.keypoints.collect()
        self.assertGreater(len(after), 5)
        self.assertTrue(all(min(t) >= 40 for _, t in after.values()), "c_min = 40 refused after a bad value")
        nan = client.update_configuration({"threshold_scale": float("nan")})
        self.assertEqual(nan["threshold_scale"], config["threshold_scale"], "NaN is reported as running")

    def test_changing_beta_changes_the_enhanced_image(self):
        # gamma_mode always (the default mode's): the brightness mask T_mask, weighted by beta, is applied.
        self.apply("/cam0/enhance", {"gamma_mode": "always", "beta": 0.0})
        before = self.enhanced.collect()
        self.apply("/cam0/enhance", {"beta": 1.0})
        after = self.enhanced.collect()
        common = set(before) & set(after)
        self.assertGreater(len(common), 20)
        for stamp in common:
            self.assertNotEqual(before[stamp], after[stamp], "frame %s unchanged by beta" % stamp)


if __name__ == "__main__":
    rospy.init_node("check_reconfigure")
    rostest.rosrun("enhanced_orb", "check_reconfigure", Reconfigure)
