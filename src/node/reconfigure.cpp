#include "mass_aggregate_sim/node/reconfigure.h"

#include <tuple>

namespace mass_aggregate_sim {
namespace node {
namespace {

auto physicsTie(const LiveSettings& s) {
  return std::tie(s.rate, s.substeps, s.integrator, s.gravity.x(), s.gravity.y(), s.gravity.z(),
                  s.auto_substep, s.divergence_policy, s.particle_collisions, s.continuous,
                  s.particle_restitution, s.particle_friction, s.max_iterations, s.penetration_slop,
                  s.body_substeps, s.body_iterations, s.body_relax_iterations, s.body_sleep);
}

template <typename Parameter, typename Value>
void addParameter(std::vector<Parameter>& list, const std::string& name, const Value& value) {
  Parameter parameter;
  parameter.name = name;
  parameter.value = value;
  list.push_back(parameter);
}

}  // namespace

SimConfig toSimConfig(const LiveSettings& s) {
  SimConfig c;
  c.rate = s.rate;
  c.substeps = s.substeps;
  c.integrator = s.integrator;
  c.gravity_x = s.gravity.x();
  c.gravity_y = s.gravity.y();
  c.gravity_z = s.gravity.z();
  c.auto_substep = s.auto_substep;
  c.divergence_policy = s.divergence_policy;
  c.particle_collisions = s.particle_collisions;
  c.continuous = s.continuous;
  c.particle_restitution = s.particle_restitution;
  c.particle_friction = s.particle_friction;
  c.max_iterations = s.max_iterations;
  c.penetration_slop = s.penetration_slop;
  c.body_substeps = s.body_substeps;
  c.body_iterations = s.body_iterations;
  c.body_relax_iterations = s.body_relax_iterations;
  c.body_sleep = s.body_sleep;
  c.publish_rate = s.publish_rate;
  c.paused = s.paused;
  return c;
}

LiveSettings fromSimConfig(const SimConfig& c) {
  LiveSettings s;
  s.rate = c.rate;
  s.substeps = c.substeps;
  s.integrator = c.integrator;
  s.gravity = engine::Vec3(c.gravity_x, c.gravity_y, c.gravity_z);
  s.auto_substep = c.auto_substep;
  s.divergence_policy = c.divergence_policy;
  s.particle_collisions = c.particle_collisions;
  s.continuous = c.continuous;
  s.particle_restitution = c.particle_restitution;
  s.particle_friction = c.particle_friction;
  s.max_iterations = c.max_iterations;
  s.penetration_slop = c.penetration_slop;
  s.body_substeps = c.body_substeps;
  s.body_iterations = c.body_iterations;
  s.body_relax_iterations = c.body_relax_iterations;
  s.body_sleep = c.body_sleep;
  s.publish_rate = c.publish_rate;
  s.paused = c.paused;
  return s;
}

dynamic_reconfigure::Config toRecordedConfig(const LiveSettings& s) {
  dynamic_reconfigure::Config c;
  addParameter(c.doubles, "rate", s.rate);
  addParameter(c.doubles, "gravity_x", s.gravity.x());
  addParameter(c.doubles, "gravity_y", s.gravity.y());
  addParameter(c.doubles, "gravity_z", s.gravity.z());
  addParameter(c.doubles, "particle_restitution", s.particle_restitution);
  addParameter(c.doubles, "particle_friction", s.particle_friction);
  addParameter(c.doubles, "penetration_slop", s.penetration_slop);
  addParameter(c.ints, "substeps", s.substeps);
  addParameter(c.ints, "max_iterations", s.max_iterations);
  addParameter(c.ints, "body_substeps", s.body_substeps);
  addParameter(c.ints, "body_iterations", s.body_iterations);
  addParameter(c.ints, "body_relax_iterations", s.body_relax_iterations);
  addParameter(c.strs, "integrator", s.integrator);
  addParameter(c.strs, "divergence_policy", s.divergence_policy);
  addParameter(c.bools, "auto_substep", s.auto_substep);
  addParameter(c.bools, "particle_collisions", s.particle_collisions);
  addParameter(c.bools, "continuous", s.continuous);
  addParameter(c.bools, "body_sleep", s.body_sleep);
  return c;
}

bool samePhysics(const LiveSettings& a, const LiveSettings& b) {
  return physicsTie(a) == physicsTie(b);
}

bool sameSettings(const LiveSettings& a, const LiveSettings& b) {
  return samePhysics(a, b) && a.publish_rate == b.publish_rate && a.paused == b.paused;
}

}  // namespace node
}  // namespace mass_aggregate_sim
