#pragma once

#include "mass_aggregate_sim/engine/core/stable_id.h"

namespace mass_aggregate_sim {
namespace engine {

struct ParticleTag;
// Names one particle (slot + generation).
using ParticleId = StableId<ParticleTag>;

}  // namespace engine
}  // namespace mass_aggregate_sim
