#!/usr/bin/env python3
"""Stops a launch (as a required node) with a clear message when a file it needs does not exist;
otherwise waits quietly until the launch ends. Used by euroc.launch for its bag."""
import os
import sys

import rospy


def main():
    args = rospy.myargv()[1:]
    if len(args) != 1:
        sys.exit("usage: require_file.py FILE")
    path = os.path.expanduser(args[0])
    if not os.path.isfile(path):
        sys.stderr.write(
            "enhanced_orb: no bag at %s\n"
            "  make the demo bag (needs Debian's visp-images-data):\n"
            "    rosrun enhanced_orb make_demo_bag.py ~/.ros/enhanced_orb_demo.bag\n"
            "    roslaunch enhanced_orb euroc.launch bag:=$HOME/.ros/enhanced_orb_demo.bag\n"
            "  or play a EuRoC bag: roslaunch enhanced_orb euroc.launch bag:=/path/to/MH_01_easy.bag\n" % path)
        sys.exit(1)
    rospy.init_node("bag_check", anonymous=True)
    rospy.spin()


if __name__ == "__main__":
    main()
