#include "mass_aggregate_sim/node/node_params.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <tuple>
#include <utility>
#include <vector>

#include "mass_aggregate_sim/engine/integrators/integrator.h"
#include "mass_aggregate_sim/node/input_limits.h"

namespace mass_aggregate_sim {
namespace node {

using engine::Result;
using engine::Status;
using engine::Vec3;

Result<NodeParams> readNodeParams(ros::NodeHandle& nh) {
  NodeParams p;
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
           {"max_bodies", ParamType::kInt},
           {"max_joints", ParamType::kInt},
           {"contact_markers", ParamType::kBool},
           {"diagnostic_period", ParamType::kNumber},
           {"rate", ParamType::kNumber},
           {"substeps", ParamType::kInt},
           {"integrator", ParamType::kString},
           {"gravity", ParamType::kVec3}}) {
    XmlRpc::XmlRpcValue value;
    if (!nh.getParam(name, value)) continue;
    const Status typed = checkParamType(name, value, type);
    if (!typed) return typed;
    p.given.push_back(name);
  }
  nh.param("publish_rate", p.publish_rate, p.publish_rate);
  nh.param("diagnostic_period", p.diagnostic_period, p.diagnostic_period);
  nh.param("frame_id", p.frame_id, p.frame_id);
  nh.param("paused", p.paused, p.paused);
  nh.param("publish_clock", p.publish_clock, p.publish_clock);
  nh.param("publish_tf", p.publish_tf, p.publish_tf);
  nh.param("default_radius", p.default_radius, p.default_radius);
  nh.param("tension_scale", p.tension_scale, p.tension_scale);
  nh.param("contact_markers", p.contact_markers, p.contact_markers);
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
  int max_bodies = static_cast<int>(p.limits.max_bodies);
  nh.param("max_bodies", max_bodies, max_bodies);
  int max_joints = static_cast<int>(p.limits.max_joints);
  nh.param("max_joints", max_joints, max_joints);
  if (!(p.publish_rate > 0.0 && p.publish_rate <= 1000.0)) {
    return Status::error("~publish_rate: must be in (0, 1000] Hz");
  }
  if (!(p.diagnostic_period > 0.0 && p.diagnostic_period <= 3600.0)) {
    return Status::error("~diagnostic_period: must be in (0, 3600] s");
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
        {"max_sustained_forces", max_sustained, kMaxSustainedForcesLimit},
        {"max_bodies", max_bodies, kMaxBodiesLimit},
        {"max_joints", max_joints, kMaxJointsLimit}}) {
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
  p.limits.max_bodies = static_cast<std::size_t>(max_bodies);
  p.limits.max_joints = static_cast<std::size_t>(max_joints);
  p.limits.world_frame = p.frame_id;
  return p;
}

namespace {

std::string number(const double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

std::string vector(const Vec3& v) {
  return "[" + number(v.x()) + ", " + number(v.y()) + ", " + number(v.z()) + "]";
}

std::string flag(const bool value) { return value ? "true" : "false"; }

}  // namespace

std::string describeParameters(const NodeParams& p, const LoadedScene& scene) {
  const NodeParams d;
  std::string out;
  const auto item = [&](const char* name, const bool differs, const std::string& value,
                        const std::string& instead) {
    if (!differs || std::find(p.given.begin(), p.given.end(), name) == p.given.end()) return;
    if (!out.empty()) out += ", ";
    out += std::string("~") + name + " = " + value + " (" + instead + ")";
  };
  const auto node = [](const std::string& value) { return "default: " + value; };
  const SceneStepSettings& own = scene.own;
  const auto from = [](const bool given, const std::string& value) {
    return (given ? "scene: " : "default: ") + value;
  };
  const engine::WorldConfig& config = scene.world.config();
  const auto own_integrator = engine::parseIntegrator(own.integrator);
  item("rate", scene.rate != own.rate, number(scene.rate), from(own.rate_given, number(own.rate)));
  item("substeps", config.substeps != own.substeps, std::to_string(config.substeps),
       from(own.substeps_given, std::to_string(own.substeps)));
  item("integrator", !own_integrator || *own_integrator != config.integrator,
       engine::integratorName(config.integrator), from(own.integrator_given, own.integrator));
  item("gravity", config.gravity != own.gravity, vector(config.gravity),
       from(own.gravity_given, vector(own.gravity)));
  item("publish_rate", p.publish_rate != d.publish_rate, number(p.publish_rate),
       node(number(d.publish_rate)));
  item("paused", p.paused != d.paused, flag(p.paused), node(flag(d.paused)));
  item("publish_clock", p.publish_clock != d.publish_clock, flag(p.publish_clock),
       node(flag(d.publish_clock)));
  item("publish_tf", p.publish_tf != d.publish_tf, flag(p.publish_tf), node(flag(d.publish_tf)));
  item("frame_id", p.frame_id != d.frame_id, quoteInput(p.frame_id), node(quoteInput(d.frame_id)));
  item("default_radius", p.default_radius != d.default_radius, number(p.default_radius),
       node(number(d.default_radius)));
  item("tension_scale", p.tension_scale != d.tension_scale, number(p.tension_scale),
       node(number(d.tension_scale)));
  item("contact_markers", p.contact_markers != d.contact_markers, flag(p.contact_markers),
       node(flag(d.contact_markers)));
  item("diagnostic_period", p.diagnostic_period != d.diagnostic_period, number(p.diagnostic_period),
       node(number(d.diagnostic_period)));
  const SimulationLimits& l = p.limits;
  const SimulationLimits& dl = d.limits;
  item("max_particles", l.max_particles != dl.max_particles, std::to_string(l.max_particles),
       node(std::to_string(dl.max_particles)));
  item("max_steps_per_request", l.max_steps_per_request != dl.max_steps_per_request,
       std::to_string(l.max_steps_per_request), node(std::to_string(dl.max_steps_per_request)));
  const std::uint32_t service_default = std::min(d.max_service_steps, l.max_steps_per_request);
  item("max_service_steps", p.max_service_steps != service_default,
       std::to_string(p.max_service_steps), node(std::to_string(service_default)));
  item("max_links", l.max_links != dl.max_links, std::to_string(l.max_links),
       node(std::to_string(dl.max_links)));
  item("max_sustained_forces", l.max_sustained_forces != dl.max_sustained_forces,
       std::to_string(l.max_sustained_forces), node(std::to_string(dl.max_sustained_forces)));
  item("max_bodies", l.max_bodies != dl.max_bodies, std::to_string(l.max_bodies),
       node(std::to_string(dl.max_bodies)));
  item("max_joints", l.max_joints != dl.max_joints, std::to_string(l.max_joints),
       node(std::to_string(dl.max_joints)));
  return out;
}

Result<LoadedScene> readScene(ros::NodeHandle& nh, const NodeParams& params) {
  SceneOverrides overrides;
  overrides.max_particles = params.limits.max_particles;
  overrides.max_links = params.limits.max_links;
  overrides.max_bodies = params.limits.max_bodies;
  overrides.max_joints = params.limits.max_joints;
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
