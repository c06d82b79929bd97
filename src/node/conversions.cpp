#include "mass_aggregate_sim/node/conversions.h"

#include <cmath>
#include <string>

namespace mass_aggregate_sim {
namespace node {

geometry_msgs::Point toPointMsg(const engine::Vec3& v) {
  geometry_msgs::Point p;
  p.x = v.x();
  p.y = v.y();
  p.z = v.z();
  return p;
}

geometry_msgs::Vector3 toVector3Msg(const engine::Vec3& v) {
  geometry_msgs::Vector3 m;
  m.x = v.x();
  m.y = v.y();
  m.z = v.z();
  return m;
}

engine::Vec3 fromMsg(const geometry_msgs::Point& p) { return engine::Vec3(p.x, p.y, p.z); }
engine::Vec3 fromMsg(const geometry_msgs::Vector3& v) { return engine::Vec3(v.x, v.y, v.z); }

void fillParticleArray(const WorldSnapshot& world, ParticleArray& msg) {
  const std::size_t n = world.ids.size();
  msg.step = world.step;
  msg.time = world.time;
  msg.particles.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    Particle& p = msg.particles[i];
    p.id = world.ids[i];
    p.name = world.names[i];
    p.position = toPointMsg(world.positions.col(i));
    p.velocity = toVector3Msg(world.velocities.col(i));
    p.mass = world.inverse_masses[i] > 0.0 ? 1.0 / world.inverse_masses[i] : 0.0;
    p.radius = world.radii[i];
  }
}

engine::Result<engine::ParticleSpec> toParticleSpec(const ParticleSpec& msg,
                                                    const double default_radius) {
  engine::ParticleSpec spec;
  if (!msg.fixed && !(std::isfinite(msg.mass) && msg.mass > 0.0)) {
    return engine::Status::error("mass must be finite and > 0 (or fixed true), got " +
                                 std::to_string(msg.mass));
  }
  spec.inverse_mass = msg.fixed ? 0.0 : 1.0 / msg.mass;
  spec.position = fromMsg(msg.position);
  spec.velocity = fromMsg(msg.velocity);
  spec.radius = msg.radius == 0.0 ? default_radius : msg.radius;
  spec.damping = msg.damping == 0.0 ? 1.0 : msg.damping;
  spec.name = msg.name;
  if (msg.fixed && !spec.velocity.isZero(0.0)) {
    return engine::Status::error("a fixed particle cannot have a velocity");
  }
  const engine::Status valid = engine::validateSpec(spec);
  if (!valid) return valid;
  return spec;
}

}  // namespace node
}  // namespace mass_aggregate_sim
