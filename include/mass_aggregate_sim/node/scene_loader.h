#pragma once

#include <xmlrpcpp/XmlRpcValue.h>

#include <cstddef>
#include <optional>
#include <string>

#include "mass_aggregate_sim/engine/world/world.h"
#include "mass_aggregate_sim/node/joint_requests.h"

namespace mass_aggregate_sim {
namespace node {

// Node parameters that, when set, win over what the scene says.
struct SceneOverrides {
  std::optional<double> rate;  // Hz: physics steps per second, dt = 1 / rate
  std::optional<int> substeps;
  std::optional<std::string> integrator;
  std::optional<engine::Vec3> gravity;  // m/s^2
  std::size_t max_particles = 20000;
  std::size_t max_links = 100000;  // force generators and links together
  std::size_t max_bodies = 10000;
  std::size_t max_joints = 10000;
  std::string world_frame = "world";  // no particle or body may be named as it (tf would clash)
};

// A scene's step settings before the node parameters override them: its own value where it
// gives one (`given`), else the default.
struct SceneStepSettings {
  double rate = 60.0;  // Hz
  int substeps = 1;
  std::string integrator = "semi_implicit_euler";
  engine::Vec3 gravity = engine::Vec3(0.0, 0.0, -9.81);  // m/s^2
  bool rate_given = false;
  bool substeps_given = false;
  bool integrator_given = false;
  bool gravity_given = false;
};

struct LoadedScene {
  std::string name;
  std::string description;
  // Where it came from, for the startup log line, e.g. "the parameter /mass_aggregate_sim/scene".
  std::string source;
  double rate = 60.0;     // Hz
  SceneStepSettings own;  // what ~rate, ~substeps, ~integrator and ~gravity overrode
  engine::World world;
  JointNames joint_names;  // the joints the scene named
};

// Builds a world from a scene tree (the value of ~scene on the parameter server; an empty or
// missing tree is an empty scene). A bad scene is refused with the key and the reason, e.g.
// "scene.particles[2].mass: must be > 0".
//
// Precedence: an override (node parameter) > the scene's own value > the default
// (rate 60 Hz, 1 substep, semi_implicit_euler, gravity [0, 0, -9.81]).
engine::Result<LoadedScene> loadScene(const XmlRpc::XmlRpcValue& scene,
                                      const SceneOverrides& overrides);

}  // namespace node
}  // namespace mass_aggregate_sim
