#pragma once
// Whether every value of two arrays is finite, in one vectorised pass (the divergence check that
// runs after every step the energy guard does not judge).

#include <cstddef>

#include "mass_aggregate_sim/engine/core/types.h"

namespace mass_aggregate_sim {
namespace engine {

// True when a[0..count) and b[0..count) hold no Inf and no NaN.
bool allFinite(const Real* a, const Real* b, std::size_t count);

}  // namespace engine
}  // namespace mass_aggregate_sim
