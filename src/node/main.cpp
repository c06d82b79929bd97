#include <ros/ros.h>

#include "mass_aggregate_sim/node/sim_node.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "mass_aggregate_sim");
  ros::NodeHandle private_nh("~");
  namespace node = mass_aggregate_sim::node;

  const auto params = node::readNodeParams(private_nh);
  if (!params) {
    ROS_FATAL("bad parameter: %s", params.message().c_str());
    return 1;
  }
  const auto scene = node::readScene(private_nh, *params);
  if (!scene) {
    ROS_FATAL("bad scene: %s", scene.message().c_str());
    return 1;
  }
  node::SimNode sim_node(private_nh, *scene, *params);
  sim_node.run();
  return 0;
}
