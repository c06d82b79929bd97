#pragma once

#include <ros/ros.h>
#include <std_srvs/SetBool.h>
#include <std_srvs/Trigger.h>
#include <tf2_ros/static_transform_broadcaster.h>
#include <tf2_ros/transform_broadcaster.h>
#include <tf2_ros/transform_listener.h>

#include <Eigen/Geometry>
#include <chrono>
#include <memory>
#include <string>

#include "mass_aggregate_sim/AddLink.h"
#include "mass_aggregate_sim/ApplyForce.h"
#include "mass_aggregate_sim/ApplyImpulse.h"
#include "mass_aggregate_sim/Remove.h"
#include "mass_aggregate_sim/RemoveLink.h"
#include "mass_aggregate_sim/SetState.h"
#include "mass_aggregate_sim/Spawn.h"
#include "mass_aggregate_sim/Step.h"
#include "mass_aggregate_sim/node/markers.h"
#include "mass_aggregate_sim/node/request_queue.h"
#include "mass_aggregate_sim/node/scene_loader.h"
#include "mass_aggregate_sim/node/simulation.h"

namespace mass_aggregate_sim {
namespace node {

struct NodeParams {
  double publish_rate = 30.0;  // Hz, wall
  std::string frame_id = "world";
  bool paused = false;
  bool publish_clock = false;
  bool publish_tf = true;
  double default_radius = 0.1;  // m
  double tension_scale = 10.0;  // N, link colour saturation
  SimulationLimits limits;
};

// The ROS adapter. Threading: run() is the one thread that owns the world; it wakes on a
// fixed-rate wall schedule, applies the queued requests (RequestQueue) at the step boundary,
// steps, and publishes. Service callbacks run on an AsyncSpinner thread: they check and
// transform their request (tf2), queue a job and block until the world thread has applied it.
class SimNode {
 public:
  SimNode(ros::NodeHandle& private_nh, const LoadedScene& scene, const NodeParams& params);
  // Steps until ROS shuts down.
  void run();

 private:
  using Clock = std::chrono::steady_clock;

  bool onSpawn(Spawn::Request& req, Spawn::Response& res);
  bool onRemove(Remove::Request& req, Remove::Response& res);
  bool onSetState(SetState::Request& req, SetState::Response& res);
  bool onApplyForce(ApplyForce::Request& req, ApplyForce::Response& res);
  bool onApplyImpulse(ApplyImpulse::Request& req, ApplyImpulse::Response& res);
  bool onAddLink(AddLink::Request& req, AddLink::Response& res);
  bool onRemoveLink(RemoveLink::Request& req, RemoveLink::Response& res);
  bool onPause(std_srvs::SetBool::Request& req, std_srvs::SetBool::Response& res);
  bool onStep(Step::Request& req, Step::Response& res);
  bool onReset(std_srvs::Trigger::Request& req, std_srvs::Trigger::Response& res);

  // Queues the job for the world thread and waits; false (with the message set) when the node
  // is shutting down.
  template <typename Response>
  bool runOnWorldThread(Response& res, std::function<void()> job);
  // The transform from `frame` to ~frame_id (identity for an empty frame or ~frame_id itself).
  engine::Result<Eigen::Isometry3d> frameToWorld(const std::string& frame) const;
  // Publishes an accepted request on ~commands, stamped with the step it was applied at.
  template <typename Request>
  void recordCommand(const std::string& service, const Request& request);

  void tick();
  void stepOnce();
  void publishClock();
  void publishState(Clock::time_point now);
  void publishTf(const ros::Time& stamp);
  // One static frame per collider, <frame_id>/collider_<id>, published once.
  void publishColliderFrames();
  ros::Time clockTime() const;

  NodeParams params_;
  std::string scene_name_;
  double rate_;
  Simulation sim_;
  bool paused_;
  std::uint64_t scene_hash_;
  RequestQueue queue_;
  MarkerBuilder markers_;

  ros::NodeHandle nh_;
  ros::Publisher particles_pub_;
  ros::Publisher markers_pub_;
  ros::Publisher stats_pub_;
  ros::Publisher commands_pub_;
  ros::Publisher clock_pub_;
  std::vector<ros::ServiceServer> services_;
  tf2_ros::Buffer tf_buffer_;
  tf2_ros::TransformListener tf_listener_;
  tf2_ros::TransformBroadcaster tf_broadcaster_;
  tf2_ros::StaticTransformBroadcaster static_broadcaster_;

  // /clock = clock_offset_ + world time: a reset adds the time reached so far to the offset, so
  // the clock never goes back.
  double clock_offset_ = 0.0;
  ros::Time last_tf_stamp_;
  std::uint64_t commands_applied_ = 0;
  std::uint64_t overruns_ = 0;
  // Per publish window, for the real-time factor and the step cost.
  Clock::time_point window_start_;
  double window_sim_time_ = 0.0;
  double window_step_cost_sum_ = 0.0;
  double window_step_cost_max_ = 0.0;
  std::uint64_t window_steps_ = 0;
};

// Reads the node parameters and the scene; the error names the parameter and the reason.
engine::Result<NodeParams> readNodeParams(ros::NodeHandle& private_nh);
engine::Result<LoadedScene> readScene(ros::NodeHandle& private_nh, const NodeParams& params);

}  // namespace node
}  // namespace mass_aggregate_sim
