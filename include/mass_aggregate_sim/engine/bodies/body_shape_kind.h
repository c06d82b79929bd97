#pragma once
// What the engine knows of a body shape kind K: BodyShapeKind<K>, specialised in K's own header
// and defined in its own source file (bodies/<kind>_shape.cpp). A shape is plain geometry in its
// own frame (centred at its origin); a body holds shapes at local poses. Every place that handles
// body shapes (mass properties, bounding boxes, the narrowphase pair table, ray casts, scenes,
// markers) visits BodyShapeKinds (body_shapes.h), so a kind that lacks one does not compile:
//   kName                        the kind's name in scenes and messages
//   fields(K&, visitor)          every field a scene sets, by name and meaning (length, extents)
//   validate(const K&)           refuses bad values (Status says why)
//   volume(k)                    m^3
//   unitInertia(k)               the inertia tensor of the shape with unit density about its
//                                centre, in its own frame (kg m^2 per kg/m^3), diagonal for these
//   aabb(k, frame)               the world box around the shape placed at frame
//   raycast(k, frame, origin, direction, max_t)
//                                the first entry of the ray (unit direction) into the shape; a ray
//                                starting inside does not hit
//   describe(k)                  how it is drawn (ShapePrimitive parts in the shape's frame)
//   submerged(k, frame, surface) the part of the shape placed at frame below a liquid surface,
//                                exact (its volume and first moment: buoyancy that rights a body)
//   rounding(k)                  the radius by which the shape is its core swept (a sphere's
//                                centre, a capsule's segment; a box: 0, its own core). A contact
//                                on it lies that far along the normal from the core's nearest
//                                point: that point turns with the body, the offset does not (a
//                                rolling ball's contact stays below its centre)

#include <optional>
#include <vector>

#include "mass_aggregate_sim/engine/bodies/submerged_volume.h"
#include "mass_aggregate_sim/engine/collision/shape_parts.h"
#include "mass_aggregate_sim/engine/core/status.h"
#include "mass_aggregate_sim/engine/core/transform.h"

namespace mass_aggregate_sim {
namespace engine {

template <typename Kind>
struct BodyShapeKind;

}  // namespace engine
}  // namespace mass_aggregate_sim
