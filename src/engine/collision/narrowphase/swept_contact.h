#pragma once
// A speculative contact between two moving shapes, made where they will touch rather than where
// they start.
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

#include "engine/collision/narrowphase/manifold.h"
#include "mass_aggregate_sim/engine/bodies/body_shapes.h"
#include "mass_aggregate_sim/engine/core/transform.h"

namespace mass_aggregate_sim {
namespace engine {

struct SweptShape {
  const AnyBodyShape& shape;
  const Frame& frame;
  Vec3 velocity;  // the body's linear velocity
};

// The contact of a and b within `margin`: collideAny's at the start, or one made where the motion
// over dt makes them touch or on its way past; none when they move apart faster than their gap.
Manifold sweptContact(const SweptShape& a, const SweptShape& b, Real margin, Real dt);

}  // namespace engine
}  // namespace mass_aggregate_sim
