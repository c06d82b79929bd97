#pragma once

#include <cstdint>
#include <vector>

#include "mass_aggregate_sim/engine/bodies/body_spec.h"
#include "mass_aggregate_sim/engine/collision/shape_kind.h"
#include "mass_aggregate_sim/engine/core/particle_id.h"

namespace mass_aggregate_sim {
namespace engine {

// A body's contact as of the last step, for users (the node's ~contacts): body a's shape against
// another body, a static collider or a particle, the normal from a to the other side, and per
// point where it is, how far apart the surfaces were (< 0: overlap) and the impulses of the last
// substep (normal >= 0, and friction along the surface: the impulse body a gives the other side,
// which gives body a the opposite). The solver's friction acts on the contact as a whole (a force
// at the points' centre and a torque about the normal); the points' friction impulses are its
// least-norm split, with the same sum and the same torque (a one-point contact's torque, from
// BodySettings::min_twist_lever, has no second point to act through and is not in its point).
struct BodyContactReport {
  enum class Other : std::uint8_t { kBody, kCollider, kParticle };
  BodyId body;
  Other other = Other::kBody;
  BodyId other_body;
  ColliderId collider = 0;
  ParticleId particle;
  Vec3 normal = Vec3::UnitZ();
  struct Point {
    Vec3 position = Vec3::Zero();
    Real separation = 0.0;
    Real normal_impulse = 0.0;
    Vec3 friction_impulse = Vec3::Zero();
  };
  std::vector<Point> points;
};

}  // namespace engine
}  // namespace mass_aggregate_sim
