#!/usr/bin/env python3
"""Makes the package's demo bag from real camera frames that a Debian package ships.

The 218 real 640x480 frames of ViSP-images/mbt/cube (Debian package visp-images-data) are played
at 20 Hz on /cam0/image_raw (sensor_msgs/Image mono8, frame_id cam0), like a EuRoC camera, while
the lighting ramps from -60 % to +60 % brightness and back: I' = saturate(I (1 + s)).
The output depends on nothing but the input frames: running it twice gives the same messages.
"""
import argparse
import glob
import os
import sys

import cv2
import numpy as np
import rosbag
import rospy
from sensor_msgs.msg import Image

DEFAULT_FRAMES = "/usr/share/visp-images-data/ViSP-images/mbt/cube"
RATE_HZ = 20.0
START_S = 1600000000  # a fixed start stamp, so that the bag is the same on every machine


def brightness_ramp(count, extreme=0.6):
    """s for each frame: -extreme up to +extreme over the first half, and back down."""
    half = count // 2
    up = np.linspace(-extreme, extreme, half)
    down = np.linspace(extreme, -extreme, count - half)
    return np.concatenate([up, down])


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("output", help="bag file to write")
    parser.add_argument("--frames", default=DEFAULT_FRAMES, help="folder of image*.pgm frames (default: %(default)s)")
    args = parser.parse_args()

    files = sorted(glob.glob(os.path.join(args.frames, "image*.pgm")))
    if not files:
        sys.exit(f"make_demo_bag: no image*.pgm under {args.frames} (apt-get install visp-images-data)")
    ramp = brightness_ramp(len(files))
    tmp = args.output + ".part"
    with rosbag.Bag(tmp, "w") as bag:
        for i, (path, s) in enumerate(zip(files, ramp)):
            frame = cv2.imread(path, cv2.IMREAD_GRAYSCALE)
            if frame is None:
                sys.exit(f"make_demo_bag: cannot read {path}")
            lit = np.clip(np.rint(frame.astype(np.float64) * (1.0 + s)), 0, 255).astype(np.uint8)
            msg = Image()
            msg.header.seq = i
            msg.header.stamp = rospy.Time(START_S) + rospy.Duration.from_sec(i / RATE_HZ)
            msg.header.frame_id = "cam0"
            msg.height, msg.width = lit.shape
            msg.encoding = "mono8"
            msg.step = msg.width
            msg.data = lit.tobytes()
            bag.write("/cam0/image_raw", msg, msg.header.stamp)
    os.replace(tmp, args.output)
    print(f"make_demo_bag: wrote {len(files)} frames at {RATE_HZ:g} Hz to {args.output}")


if __name__ == "__main__":
    main()
