#pragma once
// Whether every value of two arrays is finite, in one vectorised pass (the divergence check that
// runs after every step the energy guard does not judge).

#include <cstddef>

#include "mass_aggregate_sim/engine/core/types.h"

namespace mass_aggregate_sim {
namespace engine {

// A term of the finite probe: 0 * value is 0 for every finite value and NaN for Inf or NaN, and a
// NaN stays in a sum, so a sum of these terms is 0 exactly when every value is finite. T: Real or
// a vector of them.
template <typename T>
inline T finiteProbeTerm(const T a, const T b) {
  return a * 0.0 + b * 0.0;
}

// True when a[0..count) and b[0..count) hold no Inf and no NaN.
bool allFinite(const Real* a, const Real* b, std::size_t count);

}  // namespace engine
}  // namespace mass_aggregate_sim
