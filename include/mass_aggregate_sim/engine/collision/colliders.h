#pragma once

#include "mass_aggregate_sim/engine/collision/box.h"
#include "mass_aggregate_sim/engine/collision/capsule.h"
#include "mass_aggregate_sim/engine/collision/cylinder.h"
#include "mass_aggregate_sim/engine/collision/plane.h"
#include "mass_aggregate_sim/engine/collision/sphere.h"
#include "mass_aggregate_sim/engine/core/kind_list.h"

namespace mass_aggregate_sim {
namespace engine {

// Every static collider shape, in the order particles are tested against them.
using ShapeKinds =
    KindList<PlaneCollider, SphereCollider, BoxCollider, CapsuleCollider, CylinderCollider>;

// A world's static colliders: one array per shape.
using Colliders = KindArrays<ShapeKinds>;

}  // namespace engine
}  // namespace mass_aggregate_sim
