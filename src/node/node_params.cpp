#include "mass_aggregate_sim/node/node_params.h"

#include <algorithm>
#include <cmath>
#include <tuple>
#include <utility>
#include <vector>

#include "mass_aggregate_sim/node/input_limits.h"

namespace mass_aggregate_sim {
namespace node {

using engine::Result;
using engine::Status;
using engine::Vec3;

Result<NodeParams> readNodeParams(ros::NodeHandle& nh) {
  for (const auto& [name, type] : std::initializer_list<std::pair<const char*, ParamType>>{
           {"publish_rate", ParamType::kNumber},
           {"frame_id", ParamType::kString},
           {"paused", ParamType::kBool},
           {"publish_clock", ParamType::kBool},
           {"publish_tf", ParamType::kBool},
           {"default_radius", ParamType::kNumber},
           {"tension_scale", ParamType::kNumber},
           {"max_particles", ParamType::kInt},
           {"max_steps_per_request", ParamType::kInt},
           {"max_service_steps", ParamType::kInt},
           {"max_links", ParamType::kInt},
           {"max_sustained_forces", ParamType::kInt},
           {"rate", ParamType::kNumber},
           {"substeps", ParamType::kInt},
           {"integrator", ParamType::kString},
           {"gravity", ParamType::kVec3}}) {
    XmlRpc::XmlRpcValue value;
    if (!nh.getParam(name, value)) continue;
    const Status typed = checkParamType(name, value, type);
    if (!typed) return typed;
  }
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
  int max_service_steps = static_cast<int>(p.max_service_steps);
  nh.param("max_service_steps", max_service_steps, max_service_steps);
  int max_links = static_cast<int>(p.limits.max_links);
  nh.param("max_links", max_links, max_links);
  int max_sustained = static_cast<int>(p.limits.max_sustained_forces);
  nh.param("max_sustained_forces", max_sustained, max_sustained);
  if (!(p.publish_rate > 0.0 && p.publish_rate <= 1000.0)) {
    return Status::error("~publish_rate: must be in (0, 1000] Hz");
  }
  if (p.frame_id.empty()) return Status::error("~frame_id: must not be empty");
  if (!(p.default_radius >= 0.0 && p.default_radius <= kMaxRadius)) {
    return Status::error("~default_radius: must be in [0, " + std::to_string(kMaxRadius) + "] m");
  }
  if (!(p.tension_scale > 0.0 && std::isfinite(p.tension_scale))) {
    return Status::error("~tension_scale: must be finite and > 0");
  }
  const Status name = checkParticleName(p.frame_id, "");
  if (!name) return Status::error("~frame_id: " + name.message());
  for (const auto& [key, value, limit] :
       {std::tuple<const char*, int, int>{"max_particles", max_particles, kMaxParticlesLimit},
        {"max_steps_per_request", max_steps, kMaxStepsPerRequestLimit},
        {"max_links", max_links, kMaxLinksLimit},
        {"max_sustained_forces", max_sustained, kMaxSustainedForcesLimit}}) {
    if (value < 1 || value > limit) {
      return Status::error("~" + std::string(key) + ": must be in [1, " + std::to_string(limit) +
                           "], got " + std::to_string(value));
    }
  }
  if (!nh.hasParam("max_service_steps")) max_service_steps = std::min(max_service_steps, max_steps);
  if (max_service_steps < 1 || max_service_steps > max_steps) {
    return Status::error("~max_service_steps: must be in [1, ~max_steps_per_request (" +
                         std::to_string(max_steps) + ")], got " +
                         std::to_string(max_service_steps));
  }
  p.max_service_steps = static_cast<std::uint32_t>(max_service_steps);
  p.limits.max_particles = static_cast<std::size_t>(max_particles);
  p.limits.max_steps_per_request = static_cast<std::uint32_t>(max_steps);
  p.limits.max_links = static_cast<std::size_t>(max_links);
  p.limits.max_sustained_forces = static_cast<std::size_t>(max_sustained);
  p.limits.world_frame = p.frame_id;
  return p;
}

Result<LoadedScene> readScene(ros::NodeHandle& nh, const NodeParams& params) {
  SceneOverrides overrides;
  overrides.max_particles = params.limits.max_particles;
  overrides.max_links = params.limits.max_links;
  overrides.world_frame = params.frame_id;
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
  const bool given = nh.getParam("scene", scene);
  const auto loaded = loadScene(scene, overrides);
  if (!loaded) return loaded;
  // A scene an earlier launch left on the parameter server is loaded as well (sim.launch clears
  // the node's parameters first, a bare rosrun does not): the log line says where it came from.
  LoadedScene out = *loaded;
  out.source = given ? "the parameter " + nh.resolveName("scene") +
                           " (as the parameter server held it at start)"
                     : "nowhere (no parameter " + nh.resolveName("scene") + "): an empty scene";
  return out;
}

}  // namespace node
}  // namespace mass_aggregate_sim
