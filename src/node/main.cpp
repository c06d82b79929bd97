#include <ros/ros.h>

#include "mass_aggregate_sim/engine/world.h"
#include "mass_aggregate_sim/node/conversions.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "mass_aggregate_sim");
  ros::NodeHandle private_nh("~");
  namespace engine = mass_aggregate_sim::engine;

  engine::WorldConfig config;
  const double rate = private_nh.param("rate", 60.0);
  config.dt = 1.0 / rate;
  config.substeps = private_nh.param("substeps", 1);
  const std::string integrator = private_nh.param<std::string>("integrator", "semi_implicit_euler");
  const auto parsed = engine::parseIntegrator(integrator);
  if (!parsed) {
    ROS_FATAL("~integrator: unknown integrator '%s' (known: %s)", integrator.c_str(),
              engine::integratorNames().c_str());
    return 1;
  }
  config.integrator = *parsed;
  config.gravity = engine::Vec3(0.0, 0.0, -9.81);
  engine::World world(config);
  const auto status = world.setConfig(config);
  if (!status) {
    ROS_FATAL("invalid parameters: %s", status.message().c_str());
    return 1;
  }

  const std::string frame_id = private_nh.param<std::string>("frame_id", "world");
  ros::Publisher particles_pub =
      private_nh.advertise<mass_aggregate_sim::ParticleArray>("particles", 1);
  ros::WallTimer timer = private_nh.createWallTimer(ros::WallDuration(config.dt), [&](const auto&) {
    world.step();
    mass_aggregate_sim::ParticleArray msg;
    msg.header.stamp.fromSec(world.time());
    msg.header.frame_id = frame_id;
    mass_aggregate_sim::node::fillParticleArray(world, msg);
    particles_pub.publish(msg);
  });
  ros::spin();
  return 0;
}
