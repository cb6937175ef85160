// enhance_node / extract_node: one nodelet in a process of its own, for users without a manager.
// ENHANCED_ORB_NODELET names the nodelet class (set by CMake).
#include <nodelet/loader.h>
#include <ros/ros.h>

int main(int argc, char** argv) {
  ros::init(argc, argv, ENHANCED_ORB_NODE_NAME);
  nodelet::Loader loader(false);
  const nodelet::M_string remappings(ros::names::getRemappings());
  const nodelet::V_string args(argv + 1, argv + argc);
  if (!loader.load(ros::this_node::getName(), ENHANCED_ORB_NODELET, remappings, args)) {
    ROS_FATAL("could not load nodelet %s", ENHANCED_ORB_NODELET);
    return 1;
  }
  ros::spin();
  return 0;
}
