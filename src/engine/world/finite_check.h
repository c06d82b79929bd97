#pragma once
// Whether every value of two arrays is finite, in one vectorised pass (the divergence check that
// runs after every step the energy guard does not judge).

#include <cstddef>

#include "engine/core/simd.h"
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

// The probe's verdict from its four lanes and its scalar tail: every value was finite. Inlined
// into its callers' cloned functions (a 256-bit argument cannot cross into the baseline version).
inline __attribute__((always_inline)) bool probedFinite(const simd::Real4 lanes, const Real tail) {
  return ((lanes[0] + lanes[1]) + (lanes[2] + lanes[3])) + tail == 0.0;
}

// True when a[0..count) and b[0..count) hold no Inf and no NaN.
bool allFinite(const Real* a, const Real* b, std::size_t count);
// The same pass, also telling whether some b[k]^2 is above bound_squared.
bool allFinite(const Real* a, const Real* b, std::size_t count, Real bound_squared, bool& beyond);

}  // namespace engine
}  // namespace mass_aggregate_sim
