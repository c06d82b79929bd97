#pragma once

#include "mass_aggregate_sim/engine/core/kind_list.h"
#include "mass_aggregate_sim/engine/forces/body_buoyancy.h"
#include "mass_aggregate_sim/engine/forces/body_drag.h"
#include "mass_aggregate_sim/engine/forces/point_spring.h"

namespace mass_aggregate_sim {
namespace engine {

// Every kind of force generator on bodies, in the order their forces are summed.
using BodyForceKinds = KindList<BodyDrag, PointSpring, BodyBuoyancy>;

// A world's force generators on bodies: one array per kind (an empty kind costs nothing).
using BodyForceGenerators = KindArrays<BodyForceKinds>;

}  // namespace engine
}  // namespace mass_aggregate_sim
