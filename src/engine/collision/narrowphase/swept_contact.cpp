#include "engine/collision/narrowphase/swept_contact.h"

#include <algorithm>
#include <limits>

#include "engine/collision/narrowphase/any_shape.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

// Advanced to within this of touching, the contact's normal is the touch's. A ball meeting
// another obliquely gets there in a few samples, and a pass is bracketed in a few more; a pair
// still undecided after kMaxSamples gets its contact at the last sample that was closing.
constexpr Real kTouching = 1e-4;
constexpr int kMaxSamples = 12;

Real leastSeparation(const Manifold& manifold) {
  Real least = manifold.points[0].separation;
  for (int k = 1; k < manifold.count; ++k) least = std::min(least, manifold.points[k].separation);
  return least;
}

struct Sample {
  Real t;
  Manifold manifold;
  Real gap;
};

// The contact made at s.t, taken back to the step's start: each point midway between where the
// two bodies' touching points start, b's -(v_b - v_a) t from a's, its gap as much wider as the
// motion closes it by t.
Manifold takenBack(Sample s, const SweptShape& a, const SweptShape& b) {
  if (s.t == 0.0) return s.manifold;
  Manifold& manifold = s.manifold;
  const Vec3 back = -0.5 * s.t * (a.velocity + b.velocity);
  manifold.slide = -s.t * (b.velocity - a.velocity);
  const Real closed = manifold.slide.dot(manifold.normal);
  for (int k = 0; k < manifold.count; ++k) {
    manifold.points[k].point += back;
    manifold.points[k].separation += closed;
  }
  return manifold;
}

}  // namespace

Manifold sweptContact(const SweptShape& a, const SweptShape& b, const Real margin, const Real dt) {
  const Manifold at_start = collideAny(a.shape, a.frame, b.shape, b.frame, margin);
  if (at_start.count == 0) return at_start;
  const Vec3 relative = b.velocity - a.velocity;
  Sample now{0.0, at_start, leastSeparation(at_start)};
  // Touching, or too far apart to touch within the step at these speeds: the contact as it is
  // (a gap it cannot close is never pushed on, whatever its normal).
  if (now.gap <= kTouching || dt * relative.norm() <= now.gap) return at_start;
  // Moving apart from the start, faster than the gap: none (swept_contact.h).
  if (!(-relative.dot(at_start.normal) > 0.0)) return Manifold{};
  // The latest sample still closing, and the earliest known to be past the nearest approach.
  Sample closing_sample = now;
  Real opening_at = std::numeric_limits<Real>::infinity();
  for (int sample = 0; sample < kMaxSamples; ++sample) {
    // Along the normal the gap is gap - u (t' - t) at t', u = -(v_b - v_a).n. A contact whose
    // gap stays open over the whole step is not pushed on unless the solver turns the two
    // towards each other, and then across a plane near the one they pass at.
    const Real closing = -relative.dot(now.manifold.normal);
    const bool open_throughout =
        now.gap + now.t * closing >= 0.0 && now.gap - (dt - now.t) * closing >= 0.0;
    if (now.gap <= kTouching || open_throughout) return takenBack(now, a, b);
    Real next;
    if (closing > 0.0) {
      // Translating convex shapes are no nearer than that gap until t + gap / u, and the
      // distance between them is convex in time: advancing never passes a touch.
      closing_sample = now;
      next = std::min(now.t + now.gap / closing, 0.5 * (now.t + opening_at));
    } else {
      // The last advance went past the nearest approach (its gap, taken back to the start along
      // this normal, would overlap): halve the bracket.
      opening_at = now.t;
      next = 0.5 * (closing_sample.t + now.t);
    }
    const Manifold at_next =
        collideAny(a.shape, Frame(a.frame.position + next * a.velocity, a.frame.rotation), b.shape,
                   Frame(b.frame.position + next * b.velocity, b.frame.rotation), margin);
    if (at_next.count == 0) {
      // Beyond the margin at next, nearer at the closing sample: the nearest approach is before.
      opening_at = next;
      now = closing_sample;
      continue;
    }
    now = Sample{next, at_next, leastSeparation(at_next)};
  }
  return takenBack(closing_sample, a, b);
}

}  // namespace engine
}  // namespace mass_aggregate_sim
