#include "engine/collision/narrowphase/swept_contact.h"

#include <algorithm>

#include "engine/collision/narrowphase/any_shape.h"

namespace mass_aggregate_sim {
namespace engine {
namespace swept {

Real leastSeparation(const Manifold& manifold) {
  Real least = manifold.points[0].separation;
  for (int k = 1; k < manifold.count; ++k) least = std::min(least, manifold.points[k].separation);
  return least;
}

Manifold takenBack(Manifold manifold, const Real t, const Vec3& velocity_a,
                   const Vec3& velocity_b) {
  if (t == 0.0) return manifold;
  const Vec3 back = -0.5 * t * (velocity_a + velocity_b);
  manifold.slide = -t * (velocity_b - velocity_a);
  const Real closed = manifold.slide.dot(manifold.normal);
  for (int k = 0; k < manifold.count; ++k) {
    manifold.points[k].point += back;
    manifold.points[k].separation += closed;
  }
  return manifold;
}

}  // namespace swept

Manifold sweptContact(const SweptShape& a, const SweptShape& b, const Real margin, const Real dt) {
  const auto collide_at = [&](const Real t) {
    return collideAny(a.shape, advanced(a.frame, a.velocity, t), b.shape,
                      advanced(b.frame, b.velocity, t), margin);
  };
  return sweptContact(collide_at, a.velocity, b.velocity, dt);
}

}  // namespace engine
}  // namespace mass_aggregate_sim
