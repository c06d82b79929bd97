#include "engine/collision/narrowphase/swept_contact.h"

#include <algorithm>

#include "engine/collision/narrowphase/any_shape.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

// Advanced to within this of touching, the contact's normal is the touch's. A ball meeting
// another obliquely gets there in a few advances; a pair still further apart after kMaxAdvances
// gets its contact where the last advance left it.
constexpr Real kTouching = 1e-4;
constexpr int kMaxAdvances = 8;

Real leastSeparation(const Manifold& manifold) {
  Real least = manifold.points[0].separation;
  for (int k = 1; k < manifold.count; ++k) least = std::min(least, manifold.points[k].separation);
  return least;
}

}  // namespace

Manifold sweptContact(const SweptShape& a, const SweptShape& b, const Real margin,
                      const Real turning, const Real dt) {
  Manifold manifold = collideAny(a.shape, a.frame, b.shape, b.frame, margin);
  if (manifold.count == 0) return manifold;
  const Vec3 relative = b.velocity - a.velocity;
  Real gap = leastSeparation(manifold);
  // Touching, or too far apart to touch within the step at these speeds: the contact as it is
  // (a gap it cannot close is never pushed on, whatever its normal).
  if (gap <= kTouching || dt * relative.norm() <= gap) return manifold;
  Real t = 0.0;
  Manifold last_closing = manifold;
  Real last_closing_t = 0.0;
  for (int advance = 0; advance < kMaxAdvances; ++advance) {
    // Along the normal the gap closes at u: by t' the shapes are no nearer than gap - u (t' - t).
    // The distance between translating convex shapes is convex in time, and the advances never
    // pass a touch: once it opens, the shapes have passed each other without touching.
    const Real closing = -relative.dot(manifold.normal);
    if (!(closing > 0.0)) {
      if (gap > turning) return Manifold{};
      manifold = last_closing;
      t = last_closing_t;
      break;
    }
    if (t + (gap - turning) / closing >= dt) return Manifold{};
    if (t == dt) break;
    last_closing = manifold;
    last_closing_t = t;
    t = std::min(t + gap / closing, dt);
    manifold =
        collideAny(a.shape, Frame(a.frame.position + t * a.velocity, a.frame.rotation), b.shape,
                   Frame(b.frame.position + t * b.velocity, b.frame.rotation), margin);
    if (manifold.count == 0) return manifold;
    gap = leastSeparation(manifold);
    if (gap <= kTouching) break;
  }
  if (t == 0.0) return manifold;
  // Back to the start: each point midway between where the two bodies' touching points start,
  // b's -(v_b - v_a) t from a's, its gap as much wider as the motion closes it by t.
  const Vec3 back = -0.5 * t * (a.velocity + b.velocity);
  manifold.slide = -t * relative;
  const Real closed = manifold.slide.dot(manifold.normal);
  for (int k = 0; k < manifold.count; ++k) {
    manifold.points[k].point += back;
    manifold.points[k].separation += closed;
  }
  return manifold;
}

}  // namespace engine
}  // namespace mass_aggregate_sim
