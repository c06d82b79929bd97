#pragma once

#include "mass_aggregate_sim/engine/bodies/box_shape.h"
#include "mass_aggregate_sim/engine/bodies/capsule_shape.h"
#include "mass_aggregate_sim/engine/bodies/sphere_shape.h"
#include "mass_aggregate_sim/engine/core/kind_list.h"

namespace mass_aggregate_sim {
namespace engine {

// Every body shape kind. The narrowphase has a pair function for every unordered pair of these,
// and for each against a plane and against a particle (a sphere).
using BodyShapeKinds = KindList<SphereShape, BoxShape, CapsuleShape>;

// A body shape of any kind.
using AnyBodyShape = KindVariant<BodyShapeKinds>;

}  // namespace engine
}  // namespace mass_aggregate_sim
