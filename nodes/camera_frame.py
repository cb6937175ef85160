#!/usr/bin/env python3
"""Publishes a latched identity transform from ~parent (map) to each camera frame in ~frames
(cam0, cam1) on /tf_static, so that rviz has a fixed frame and shows no TF warning for a bag that
carries images only."""
import rospy
from geometry_msgs.msg import TransformStamped
from tf2_msgs.msg import TFMessage


def main():
    rospy.init_node("camera_frame")
    parent = rospy.get_param("~parent", "map")
    frames = rospy.get_param("~frames", ["cam0", "cam1"])
    pub = rospy.Publisher("/tf_static", TFMessage, queue_size=1, latch=True)
    msg = TFMessage()
    for child in frames:
        t = TransformStamped()
        t.header.stamp = rospy.Time(0)
        t.header.frame_id = parent
        t.child_frame_id = child
        t.transform.rotation.w = 1.0
        msg.transforms.append(t)
    pub.publish(msg)
    rospy.spin()


if __name__ == "__main__":
    main()
