#pragma once

#include <ros/node_handle.h>

#include <cstddef>
#include <string>
#include <vector>

#include "mass_aggregate_sim/engine/core/status.h"
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
  double default_radius = 0.1;   // m
  double tension_scale = 10.0;   // N, link colour saturation
  bool contact_markers = false;  // body contacts as arrows on ~markers
  // The ~step service's limit: it answers when its steps are done, so it is for short runs;
  // longer ones go through the ~step action (up to limits.max_steps_per_request).
  std::uint32_t max_service_steps = 1000;
  double diagnostic_period = 1.0;  // s, wall
  SimulationLimits limits;
  // The parameters found on the parameter server at start (without the leading ~), in the order
  // they are read; the startup line names those that changed a default.
  std::vector<std::string> given;
};

// Reads the node parameters (~publish_rate, ~frame_id, ...); the error names the parameter.
engine::Result<NodeParams> readNodeParams(ros::NodeHandle& private_nh);
// The parameters read from the parameter server whose value differs from what the node would
// have run without them, e.g. "~rate = 1 (scene: 100), ~paused = true (default: false)"; empty
// when there is none. A bare `rosrun` reads what an earlier node or reconfigure left on the
// master, so the startup line names them.
std::string describeParameters(const NodeParams& params, const LoadedScene& scene);
// Reads ~scene with ~rate, ~substeps, ~integrator and ~gravity as overrides; the error names the
// key and the reason.
engine::Result<LoadedScene> readScene(ros::NodeHandle& private_nh, const NodeParams& params);

}  // namespace node
}  // namespace mass_aggregate_sim
