#include "mass_aggregate_sim/node/node_params.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace mass_aggregate_sim {
namespace node {

using engine::Result;
using engine::Status;
using engine::Vec3;

Result<NodeParams> readNodeParams(ros::NodeHandle& nh) {
  NodeParams p;
  nh.param("publish_rate", p.publish_rate, p.publish_rate);
  nh.param("frame_id", p.frame_id, p.frame_id);
  nh.param("paused", p.paused, p.paused);
  nh.param("publish_clock", p.publish_clock, p.publish_clock);
  nh.param("publish_tf", p.publish_tf, p.publish_tf);
  nh.param("default_radius", p.default_radius, p.default_radius);
  nh.param("tension_scale", p.tension_scale, p.tension_scale);
  int max_particles = static_cast<int>(p.limits.max_particles);
  nh.param("max_particles", max_particles, max_particles);
  int max_steps = static_cast<int>(p.limits.max_steps_per_request);
  nh.param("max_steps_per_request", max_steps, max_steps);
  if (!(p.publish_rate > 0.0 && p.publish_rate <= 1000.0)) {
    return Status::error("~publish_rate: must be in (0, 1000] Hz");
  }
  if (p.frame_id.empty()) return Status::error("~frame_id: must not be empty");
  if (!(p.default_radius >= 0.0 && std::isfinite(p.default_radius))) {
    return Status::error("~default_radius: must be finite and >= 0");
  }
  if (!(p.tension_scale > 0.0)) return Status::error("~tension_scale: must be > 0");
  if (max_particles < 1) return Status::error("~max_particles: must be >= 1");
  if (max_steps < 1) return Status::error("~max_steps_per_request: must be >= 1");
  p.limits.max_particles = static_cast<std::size_t>(max_particles);
  p.limits.max_steps_per_request = static_cast<std::uint32_t>(max_steps);
  return p;
}

Result<LoadedScene> readScene(ros::NodeHandle& nh, const std::size_t max_particles) {
  SceneOverrides overrides;
  overrides.max_particles = max_particles;
  double rate;
  if (nh.getParam("rate", rate)) overrides.rate = rate;
  int substeps;
  if (nh.getParam("substeps", substeps)) overrides.substeps = substeps;
  std::string integrator;
  if (nh.getParam("integrator", integrator) && !integrator.empty()) {
    overrides.integrator = integrator;
  }
  std::vector<double> gravity;
  if (nh.getParam("gravity", gravity)) {
    if (gravity.size() != 3 ||
        !std::all_of(gravity.begin(), gravity.end(), [](double g) { return std::isfinite(g); })) {
      return Status::error("~gravity: expected [x, y, z] of finite numbers (m/s^2)");
    }
    overrides.gravity = Vec3(gravity[0], gravity[1], gravity[2]);
  }
  XmlRpc::XmlRpcValue scene;
  nh.getParam("scene", scene);
  return loadScene(scene, overrides);
}

}  // namespace node
}  // namespace mass_aggregate_sim
