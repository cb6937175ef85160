#!/usr/bin/env python3
"""Makes the package's demo bag from real camera frames that a Debian package ships.

The 218 real 640x480 frames of ViSP-images/mbt/cube (Debian package visp-images-data) are played
at 20 Hz on /cam0/image_raw (sensor_msgs/Image mono8, frame_id cam0), like a EuRoC camera, while
the light falls from x1.6 to x0.08 and comes back (geometrically). Each frame is what a camera
would record in that light: the frame's pixels are taken as the light of a well-lit scene, the
sensor collects electrons (2 per gray level at unit gain) with shot noise and 3 electrons of read
noise, the camera raises its gain up to x4 as the light falls below x0.5, and the result is
rounded and clipped to 8 bits. The same sensor model as enhanced_orb_compare's `lowlight`.
The output depends on nothing but the input frames: the noise is seeded per frame.
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


ELECTRONS_PER_DN = 2.0
READ_NOISE_E = 3.0
MAX_GAIN = 4.0


def light_ramp(count, brightest=1.6, darkest=0.08):
    """The light of each frame: from `brightest` down to `darkest` over the first half, and back up."""
    half = count // 2
    down = np.geomspace(brightest, darkest, half)
    up = np.geomspace(darkest, brightest, count - half)
    return np.concatenate([down, up])


def camera_gain(light):
    """Auto gain: unit gain down to half the light, then up to MAX_GAIN to keep the image visible."""
    return float(np.clip(0.5 / light, 1.0, MAX_GAIN))


def expose(frame, light, seed):
    """The frame recorded in `light` times the light it was taken in, with the sensor noise."""
    rng = np.random.default_rng(seed)
    electrons = frame.astype(np.float64) * ELECTRONS_PER_DN * light
    noisy = electrons + np.sqrt(electrons) * rng.standard_normal(frame.shape) + READ_NOISE_E * rng.standard_normal(
        frame.shape)
    return np.clip(np.rint(noisy * camera_gain(light) / ELECTRONS_PER_DN), 0, 255).astype(np.uint8)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("output", help="bag file to write")
    parser.add_argument("--frames", default=DEFAULT_FRAMES, help="folder of image*.pgm frames (default: %(default)s)")
    args = parser.parse_args()

    files = sorted(glob.glob(os.path.join(args.frames, "image*.pgm")))
    if not files:
        sys.exit(f"make_demo_bag: no image*.pgm under {args.frames} (apt-get install visp-images-data)")
    ramp = light_ramp(len(files))
    tmp = args.output + ".part"
    with rosbag.Bag(tmp, "w") as bag:
        for i, (path, light) in enumerate(zip(files, ramp)):
            frame = cv2.imread(path, cv2.IMREAD_GRAYSCALE)
            if frame is None:
                sys.exit(f"make_demo_bag: cannot read {path}")
            lit = expose(frame, light, seed=i)
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
    print(f"make_demo_bag: wrote {len(files)} frames at {RATE_HZ:g} Hz to {args.output} "
          f"(light x{ramp.max():g} to x{ramp.min():g}, gain up to x{MAX_GAIN:g})")


if __name__ == "__main__":
    main()
