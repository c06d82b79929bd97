#pragma once

#include <optional>
#include <vector>

#include "mass_aggregate_sim/engine/bodies/body_spec.h"
#include "mass_aggregate_sim/engine/collision/colliders.h"
#include "mass_aggregate_sim/engine/core/particle_store.h"
#include "mass_aggregate_sim/engine/core/types.h"

namespace mass_aggregate_sim {
namespace engine {

// The first thing a ray hits: a particle (hit_particle, particle), a body (hit_body, body) or a
// collider (collider).
struct RayHit {
  bool hit_particle = false;
  ParticleId particle;
  bool hit_body = false;
  BodyId body;
  ColliderId collider = 0;
  Vec3 point = Vec3::Zero();
  Vec3 normal = Vec3::Zero();  // outward normal of what was hit, at point
  Real distance = 0.0;         // from the origin, along the normalised direction
};

// Nearest hit within max_distance of origin along direction (normalised here). Shapes and
// particles that contain the origin are not hit. Nothing for a zero or non-finite direction.
std::optional<RayHit> raycastScene(const ParticleStore& particles, const Colliders& colliders,
                                   const Vec3& origin, const Vec3& direction, Real max_distance);

// Particles whose sphere overlaps the query sphere / axis-aligned box, in dense order.
std::vector<ParticleId> particlesOverlappingSphere(const ParticleStore& particles,
                                                   const Vec3& center, Real radius);
std::vector<ParticleId> particlesOverlappingBox(const ParticleStore& particles, const Vec3& center,
                                                const Vec3& half_extents);

}  // namespace engine
}  // namespace mass_aggregate_sim
