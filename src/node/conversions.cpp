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

void fillParticleArray(const engine::World& world, ParticleArray& msg) {
  const engine::ParticleStore& particles = world.particles();
  const auto x = particles.positions();
  const auto v = particles.velocities();
  const auto inverse_mass = particles.inverseMasses();
  const auto radius = particles.radii();
  msg.step = world.stepCount();
  msg.time = world.time();
  msg.particles.resize(particles.size());
  for (std::size_t i = 0; i < particles.size(); ++i) {
    Particle& p = msg.particles[i];
    p.id = particles.idAt(i).packed();
    p.name = particles.name(i);
    p.position = toPointMsg(x.col(i));
    p.velocity = toVector3Msg(v.col(i));
    p.mass = inverse_mass[i] > 0.0 ? 1.0 / inverse_mass[i] : 0.0;
    p.radius = radius[i];
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
