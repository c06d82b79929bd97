#pragma once

#include "mass_aggregate_sim/engine/core/kind_list.h"
#include "mass_aggregate_sim/engine/forces/buoyancy.h"
#include "mass_aggregate_sim/engine/forces/drag.h"
#include "mass_aggregate_sim/engine/forces/spring.h"
#include "mass_aggregate_sim/engine/forces/stiff_spring.h"

namespace mass_aggregate_sim {
namespace engine {

// Every force generator kind, in the order their forces are summed.
using ForceKinds = KindList<Drag, Spring, Buoyancy, StiffSpring>;

// A world's force generators: one array per kind (an empty kind costs nothing).
using ForceGenerators = KindArrays<ForceKinds>;

}  // namespace engine
}  // namespace mass_aggregate_sim
