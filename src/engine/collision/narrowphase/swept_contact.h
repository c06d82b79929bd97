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
// t + d / u. They are advanced until they touch (or to the step's end) and the contact is made
// there, each point taken back to the start: p - (v_a + v_b) t / 2, separation s + u t (the
// solver closes it at u over the same t), and the sides' touching points, which the friction
// turns each body about, -(v_b - v_a) t apart (Manifold::slide). A pair that passes without
// touching, or that cannot come within `turning` of each other during dt, gets none. Rotation is
// not advanced: `turning` is how far the bodies' turning may carry their points in the step, and a
// pair passing within it keeps its contact from before they passed.
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

// The contact of a and b within `margin` (collideAny's at the start, or where the motion over dt
// makes them touch), or none when they pass each other.
Manifold sweptContact(const SweptShape& a, const SweptShape& b, Real margin, Real turning, Real dt);

}  // namespace engine
}  // namespace mass_aggregate_sim
