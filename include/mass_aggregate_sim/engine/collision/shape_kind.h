#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <optional>
#include <vector>

#include "mass_aggregate_sim/engine/bodies/body_shapes.h"
#include "mass_aggregate_sim/engine/collision/shape_parts.h"
#include "mass_aggregate_sim/engine/core/kind_list.h"
#include "mass_aggregate_sim/engine/core/status.h"
#include "mass_aggregate_sim/engine/core/transform.h"
#include "mass_aggregate_sim/engine/core/types.h"

namespace mass_aggregate_sim {
namespace engine {

// Names one static collider; never reused within a world.
using ColliderId = std::uint32_t;

// What the engine knows of a collider shape kind K: ShapeKind<K>, specialised in K's own header
// and defined in its own source file (collision/<kind>.cpp). Every stage that handles colliders
// (contacts, swept tests, queries) and the node (scenes, markers, frames) visit ShapeKinds
// (colliders.h) through these, so a kind that lacks one does not compile:
//   kName                          the kind's name in scenes and messages
//   fields(K&, visitor)            every field a scene sets, by name and meaning: the visitor's
//                                  point, direction, coordinate, length, extents, orientation
//   validate(K&)                   refuses bad values (Status says why); normalises
//   contact(k, x, r, margin)       the sphere at x of radius r against the shape; nothing when it
//                                  is farther than margin. A solid shape pushes a sphere whose
//                                  centre is inside it out the nearest way.
//   raycast(k, origin, direction, max_t, inflate)
//                                  the first entry of the ray into the shape grown by inflate (a
//                                  swept sphere's radius); a ray starting inside does not hit
//   describe(k)                    how it is drawn and where its frame is
//   bounds(k)                      the box the bodies' broadphase holds it in; none for an
//                                  unbounded shape (a plane), which every body shape meets
//   bodyContact(k, shape, frame, margin, out)
//                                  the manifold of a body shape at frame against it, normal from
//                                  the body shape to the collider (narrowphase.h)
template <typename Kind>
struct ShapeKind;

struct Manifold;

}  // namespace engine
}  // namespace mass_aggregate_sim
