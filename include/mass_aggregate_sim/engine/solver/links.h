#pragma once

#include "mass_aggregate_sim/engine/core/kind_list.h"
#include "mass_aggregate_sim/engine/solver/cable.h"
#include "mass_aggregate_sim/engine/solver/rod.h"

namespace mass_aggregate_sim {
namespace engine {

// Every link kind, in the order their constraints are listed.
using LinkKinds = KindList<Cable, Rod>;

// A world's links: one array per kind.
using Links = KindArrays<LinkKinds>;

}  // namespace engine
}  // namespace mass_aggregate_sim
