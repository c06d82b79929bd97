#pragma once
// What the narrowphase finds between two shapes: a contact manifold.

#include <array>
#include <cstdint>

#include "mass_aggregate_sim/engine/core/types.h"

namespace mass_aggregate_sim {
namespace engine {

// One contact point. separation < 0 is an overlap; a point with separation in (0, margin] is
// speculative (the shapes are that far apart along the normal). point is in world coordinates,
// midway between the two surfaces. id names the pair of features (vertex, edge, face) that made
// the point, so that the same touching features give the same id from step to step (the solver
// carries a point's impulse over by id).
struct ManifoldPoint {
  Vec3 point = Vec3::Zero();
  Real separation = 0.0;
  std::uint32_t id = 0;
};

// The contact between shape A and shape B: a normal pointing from A to B (the direction B must
// move to separate) and up to four points on one plane of contact.
struct Manifold {
  static constexpr int kMaxPoints = 4;
  Vec3 normal = Vec3::UnitZ();
  // A swept contact's (swept_contact.h): where b's touching point starts from a's (b moves that
  // much against a before they touch). The points lie midway: a's touching point is
  // point - slide / 2, b's point + slide / 2. Zero for a contact made where the shapes are.
  Vec3 slide = Vec3::Zero();
  int count = 0;
  std::array<ManifoldPoint, kMaxPoints> points{};
};

}  // namespace engine
}  // namespace mass_aggregate_sim
