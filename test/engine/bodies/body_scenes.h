#pragma once
// Bodies the acceptance tests build: z up, g = 9.81, 60 Hz unless a test says otherwise.

#include <algorithm>
#include <cmath>

#include "mass_aggregate_sim/engine/world/world.h"

namespace mass_aggregate_sim {
namespace engine {
namespace test_bodies {

constexpr Real kG = 9.81;

inline WorldConfig config(const Real gravity = kG) {
  WorldConfig c;
  c.dt = 1.0 / 60.0;
  c.gravity = Vec3(0.0, 0.0, -gravity);
  return c;
}

inline BodyShapeSpec box(const Vec3& half_extents, const Material& material = {0.0, 0.5}) {
  BodyShapeSpec s;
  s.geometry = BoxShape{half_extents};
  s.material = material;
  return s;
}

inline BodyShapeSpec sphere(const Real radius, const Material& material = {0.0, 0.5}) {
  BodyShapeSpec s;
  s.geometry = SphereShape{radius};
  s.material = material;
  return s;
}

// A dynamic body of one shape, mass given, at position with orientation q.
inline BodySpec body(const BodyShapeSpec& shape, const Real mass, const Vec3& position,
                     const Quat& q = Quat::Identity()) {
  BodySpec spec;
  spec.shapes = {shape};
  spec.mass = mass;
  spec.pose.position = position;
  spec.pose.rotation = q;
  return spec;
}

// A grain: a particle of 5 cm and 50 g at position.
constexpr Real kGrainRadius = 0.05;
inline ParticleId addGrain(World& world, const Vec3& position) {
  ParticleSpec spec;
  spec.position = position;
  spec.radius = kGrainRadius;
  spec.inverse_mass = 20.0;
  return *world.addParticle(spec);
}

// The ground: the plane z = 0 with the given material.
inline void addGround(World& world, const Material& material = {0.0, 0.5},
                      const Vec3& normal = Vec3::UnitZ()) {
  PlaneCollider ground;
  ground.normal = normal;
  ground.offset = 0.0;
  ground.material = material;
  world.addCollider(ground);
}

inline Real angleBetween(const Vec3& a, const Vec3& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

// The deepest overlap of any body contact point now (0 when none overlaps).
inline Real maxOverlap(const World& world) {
  Real worst = 0.0;
  for (const BodyContactReport& c : world.bodyContacts()) {
    for (const auto& p : c.points) worst = std::max(worst, -p.separation);
  }
  return worst;
}

}  // namespace test_bodies
}  // namespace engine
}  // namespace mass_aggregate_sim
