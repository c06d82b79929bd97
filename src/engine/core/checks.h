#pragma once
// The value checks every kind's validation shares.

#include <cmath>

#include "mass_aggregate_sim/engine/core/types.h"

namespace mass_aggregate_sim {
namespace engine {

inline bool finiteNonNegative(const Real value) { return std::isfinite(value) && value >= 0.0; }
inline bool finitePositive(const Real value) { return std::isfinite(value) && value > 0.0; }

}  // namespace engine
}  // namespace mass_aggregate_sim
