#pragma once
// A speculative contact between two moving shapes, made where they will touch rather than where
// they start: two bodies' shapes, a body's and a particle's sphere, a body's and a collider (which
// does not move).
//
// Continuous collision grows a pair's margin by how far its bodies travel in the step, so that a
// fast body meets what it is about to hit. Made at the start, such a contact's normal joins the
// shapes as they are then: between a ball falling past another it is nearly the line of the fall,
// and the solver, which lets a gap close no further than it is along the normal, stopped the ball
// on a plane the other ball never reaches and threw it sideways (a ghost collision: the rain threw
// spheres off spheres they would have missed, and more at more substeps).
//
// So a pair that could close its gap within the step (|v_b - v_a| dt > gap) is moved along the
// bodies' linear velocities by conservative advancement (Mirtich 1996): along a separating axis
// n the gap d closes at u = -(v_b - v_a).n, so translating convex shapes cannot touch before
// t + d / u. They are advanced until they touch and the contact is made there, each point taken
// back to the start: p - (v_a + v_b) t / 2, separation s + u t (the solver closes it at u over
// the same t), and the sides' touching points, which the friction turns each body about,
// -(v_b - v_a) t apart (Manifold::slide).
//
// A pair that passes without touching keeps a contact too: the first one on the way whose gap,
// taken back along its normal (s + (v_b - v_a).n t), stays open over the whole step; an advance
// that overshoots the nearest approach (the gap taken back would overlap at the start) is halved
// back towards it. At these velocities the solver does not push on that contact; it does if other
// contacts or forces turn the two towards each other within the step, and then across a plane
// nearly the one they pass at, not one across the fall. Without a contact, a ball pushed sideways
// as it passes another would go through it. Rotation is not advanced; the contact's anchors
// follow the turning in the solver.
//
// A pair moving apart at the start, faster than its gap, gets none: kept, such contacts left
// more of the random drop's piles moving at 10 s (docs/BENCHMARKS.md, session 24).
//
// A pair that cannot close its gap within the step keeps the contact made at the start: the
// solver never pushes on a gap that does not close, whatever its normal, and a resting pile's
// contacts stay as they were, with no second narrowphase call.

#include <algorithm>
#include <limits>

#include "engine/collision/narrowphase/manifold.h"
#include "mass_aggregate_sim/engine/bodies/body_shapes.h"
#include "mass_aggregate_sim/engine/core/transform.h"

namespace mass_aggregate_sim {
namespace engine {
namespace swept {

// Advanced to within this of touching, the contact's normal is the touch's. A ball meeting
// another obliquely gets there in a few samples, and a pass is bracketed in a few more; a pair
// still undecided after kMaxSamples gets its contact at the last sample that was closing.
constexpr Real kTouching = 1e-4;
constexpr int kMaxSamples = 12;

Real leastSeparation(const Manifold& manifold);

// The contact made at t, taken back to the step's start: each point midway between where the
// two sides' touching points start, b's -(v_b - v_a) t from a's, its gap as much wider as the
// motion closes it by t.
Manifold takenBack(Manifold manifold, Real t, const Vec3& velocity_a, const Vec3& velocity_b);

}  // namespace swept

// A side's frame moved t along its velocity (rotation is not advanced).
inline Frame advanced(const Frame& frame, const Vec3& velocity, const Real t) {
  return Frame(frame.position + t * velocity, frame.rotation);
}

// The contact of a pair whose sides move at velocity_a and velocity_b over dt: collide_at(t) is
// their manifold within the pair's margin with each side moved t along its velocity. The one at
// the start, or one made where the motion makes them touch or on its way past; none when they
// move apart faster than their gap.
template <typename CollideAt>
Manifold sweptContact(const CollideAt& collide_at, const Vec3& velocity_a, const Vec3& velocity_b,
                      const Real dt) {
  using swept::kMaxSamples;
  using swept::kTouching;
  struct Sample {
    Real t;
    Manifold manifold;
    Real gap;
  };
  const Manifold at_start = collide_at(0.0);
  if (at_start.count == 0) return at_start;
  const Vec3 relative = velocity_b - velocity_a;
  Sample now{0.0, at_start, swept::leastSeparation(at_start)};
  // Touching, or too far apart to touch within the step at these speeds: the contact as it is
  // (a gap it cannot close is never pushed on, whatever its normal).
  if (now.gap <= kTouching || dt * relative.norm() <= now.gap) return at_start;
  // Moving apart from the start, faster than the gap: none.
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
    if (now.gap <= kTouching || open_throughout) {
      return swept::takenBack(now.manifold, now.t, velocity_a, velocity_b);
    }
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
    const Manifold at_next = collide_at(next);
    if (at_next.count == 0) {
      // Beyond the margin at next, nearer at the closing sample: the nearest approach is before.
      opening_at = next;
      now = closing_sample;
      continue;
    }
    now = Sample{next, at_next, swept::leastSeparation(at_next)};
  }
  return swept::takenBack(closing_sample.manifold, closing_sample.t, velocity_a, velocity_b);
}

struct SweptShape {
  const AnyBodyShape& shape;
  const Frame& frame;
  Vec3 velocity;  // its body's (or particle's) linear velocity
};

// Two shapes within `margin` (collideAny's manifold): two bodies', or a body's and a particle's.
Manifold sweptContact(const SweptShape& a, const SweptShape& b, Real margin, Real dt);

}  // namespace engine
}  // namespace mass_aggregate_sim
