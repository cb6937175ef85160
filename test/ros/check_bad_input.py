#!/usr/bin/env python3
"""Sends the running pipeline every sensor_msgs encoding, degenerate and malformed images, and
extreme parameters. Each bad input has a defined outcome (output, or a warning and none); after
each, a good frame is processed and the nodelet manager is alive."""
import unittest

import dynamic_reconfigure.client
import numpy as np
import rosnode
import rospy
import rostest
from sensor_msgs.msg import Image

from pipeline_client import H, OUTPUT_S, W, PipelineClient, image, scene

MANAGER = "/cam0/enhanced_orb_manager"


G = scene()
G16 = G.astype("<u2") * 257
C3, C4 = np.dstack([G] * 3), np.dstack([G] * 4)
# name: (message, whether it is processed)
BATTERY = [
    ("mono8", image("mono8", G), True),
    ("mono16", image("mono16", G16), True),
    ("8UC1", image("8UC1", G), True),
    ("8UC3", image("8UC3", C3), False),
    ("bgr8", image("bgr8", C3), True),
    ("rgb8", image("rgb8", C3), True),
    ("bgra8", image("bgra8", C4), True),
    ("rgba8", image("rgba8", C4), True),
    ("bayer_rggb8", image("bayer_rggb8", G), True),
    ("bayer_bggr8", image("bayer_bggr8", G), True),
    ("bayer_gbrg8", image("bayer_gbrg8", G), True),
    ("bayer_grbg8", image("bayer_grbg8", G), True),
    ("bayer_rggb16", image("bayer_rggb16", G16), False),
    ("16UC1", image("16UC1", G16), True),
    ("32FC1", image("32FC1", G.astype(np.float32)), False),
    ("yuv422", image("yuv422", np.dstack([np.full_like(G, 128), G])), True),
    ("unknown encoding", image("no_such_encoding", G), False),
    ("width 0", image("mono8", G, width=0), False),
    ("height 0", image("mono8", G, height=0), False),
    ("0x0", image("mono8", np.zeros((0, 0), np.uint8), width=0, height=0, step=0), False),
    ("1x1", image("mono8", np.full((1, 1), 7, np.uint8)), True),
    ("1x500", image("mono8", scene(500, 1)), True),
    ("8000x8000", image("mono8", np.zeros((8000, 8000), np.uint8)), False),
    ("step smaller than a row", image("mono8", G, step=W - 1, data=G.tobytes()), False),
    ("step of bgr8 smaller than a row", image("bgr8", C3, step=W * 2, data=C3.tobytes()), False),
    ("data shorter than step x height", image("mono8", G, data=G.tobytes()[:-1]), False),
    ("no data", image("mono8", G, data=b""), False),
    ("padded rows", image("mono8", np.hstack([G, np.zeros((H, 13), np.uint8)]), width=W), True),
    ("data longer than needed", image("mono8", G, data=G.tobytes() + bytes(100)), True),
    ("constant black", image("mono8", np.zeros((H, W), np.uint8)), True),
    ("constant white", image("mono8", np.full((H, W), 255, np.uint8)), True),
    ("EuRoC size constant mid-grey", image("mono8", np.full((480, 752), 128, np.uint8)), True),
]
EXTREMES = [  # (node, values)
    ("/cam0/extract", {"c_min": 200}),
    ("/cam0/extract", {"c_min": 1, "threshold_scale": 0.0}),
    ("/cam0/extract", {"threshold_scale": 2.0}),
    ("/cam0/extract", {"grid_size": 32}),
    ("/cam0/extract", {"grid_size": 1}),
    ("/cam0/extract", {"n_levels": 16, "scale_factor": 2.0}),
    ("/cam0/extract", {"n_levels": 16, "scale_factor": 1.01}),
    ("/cam0/extract", {"n_levels": 1}),
    ("/cam0/extract", {"max_features": 100000}),
    ("/cam0/extract", {"max_features": 1}),
    ("/cam0/extract", {"threshold_mode": "fixed", "fast_threshold": 200}),
    ("/cam0/extract", {"threshold_mode": "fixed", "fast_threshold": 1}),
    ("/cam0/extract", {"threshold_mode": "no_such_mode"}),
    ("/cam0/extract", {"c_min": 100000, "grid_size": -5}),  # clamped by dynamic_reconfigure
    ("/cam0/extract", {"draw_grid": True, "grid_size": 32}),
    ("/cam0/enhance", {"blur_ksize": 31, "blur_sigma": 10.0}),
    ("/cam0/enhance", {"blur_ksize": 1, "blur_sigma": 0.1}),
    ("/cam0/enhance", {"blur_ksize": 4}),
    ("/cam0/enhance", {"alpha": 0.0, "tau": 0.0, "beta": 2.0, "sharpening": 5.0, "gamma_mode": "always"}),
    ("/cam0/enhance", {"alpha": 1.0, "tau": 1.0, "beta": 0.0, "sharpening": 0.0}),
    ("/cam0/enhance", {"gamma_mode": "no_such_mode"}),
    ("/cam0/enhance", {"std_threshold": 0.0, "enhance": False}),
]


class BadInput(unittest.TestCase):
    def setUp(self):
        self.client = PipelineClient()
        rospy.Subscriber("/cam0/image_annotated", Image, lambda m: None, queue_size=2)
        self.assertTrue(self.client.connected(), "no frame came through the pipeline")

    def expect_alive_and_working(self, after):
        self.assertTrue(rosnode.rosnode_ping(MANAGER, max_count=1), "the manager died after " + after)
        stamp = self.client.send(image("mono8", G))
        self.assertTrue(self.client.processed(stamp, OUTPUT_S), "the good frame after %s was not processed" % after)

    def test_battery_of_messages(self):
        for name, msg, processed in BATTERY:
            stamp = self.client.send(msg)
            got = self.client.processed(stamp, OUTPUT_S if processed else 1.0)
            self.assertEqual(got, processed, "%s: %s" % (name, "no output" if processed else "output for a bad frame"))
            self.expect_alive_and_working(name)

    def test_extreme_parameters(self):
        clients = {node: dynamic_reconfigure.client.Client(node, timeout=30) for node in ("/cam0/extract",
                                                                                          "/cam0/enhance")}
        defaults = {node: dict(c.get_configuration(timeout=10)) for node, c in clients.items()}
        for node, values in EXTREMES:
            clients[node].update_configuration(values)
            for msg in (image("mono8", G), image("mono8", scene(752, 480, seed=5))):
                stamp = self.client.send(msg)
                self.assertTrue(self.client.processed(stamp, OUTPUT_S), "no output with %s %s" % (node, values))
            self.expect_alive_and_working("%s %s" % (node, values))
            restore = {k: v for k, v in defaults[node].items() if k in values}
            clients[node].update_configuration(restore)


if __name__ == "__main__":
    rospy.init_node("check_bad_input")
    rostest.rosrun("enhanced_orb", "check_bad_input", BadInput)
