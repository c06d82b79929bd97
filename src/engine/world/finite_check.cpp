#include "engine/world/finite_check.h"

#include "engine/core/simd.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

// Inlined into the cloned functions below: Clang refuses calls that pass or return 256-bit
// vectors written directly in the baseline version of a function. With kBound, also whether some
// b[k]^2 is above `bound_squared`, as an OR of lane masks (latency 1 on the loop's chain, where a
// running maximum added one of several cycles to every four values; a NaN compares false).
template <bool kBound>
inline __attribute__((always_inline)) bool sumsToZero(const Real* a, const Real* b,
                                                      const std::size_t count,
                                                      const Real bound_squared, bool* beyond) {
  simd::Real4 sum = simd::broadcast(0.0);
  simd::Mask4 above = {0, 0, 0, 0};
  const simd::Real4 bound = simd::broadcast(bound_squared);
  std::size_t k = 0;
  for (; k + 4 <= count; k += 4) {
    const simd::Real4 bk = simd::load(b + k);
    sum += finiteProbeTerm(simd::load(a + k), bk);
    if constexpr (kBound) above |= bk * bk > bound;
  }
  Real tail = 0.0;
  bool tail_above = false;
  for (; k < count; ++k) {
    tail += finiteProbeTerm(a[k], b[k]);
    if constexpr (kBound) tail_above = tail_above || b[k] * b[k] > bound_squared;
  }
  if constexpr (kBound) *beyond = tail_above || (above[0] | above[1] | above[2] | above[3]) != 0;
  return probedFinite(sum, tail);
}

MAS_SIMD_CLONES bool zeroProbe(const Real* a, const Real* b, const std::size_t count) {
  return sumsToZero<false>(a, b, count, 0.0, nullptr);
}

MAS_SIMD_CLONES bool zeroProbeWithBound(const Real* a, const Real* b, const std::size_t count,
                                        const Real bound_squared, bool& beyond) {
  return sumsToZero<true>(a, b, count, bound_squared, &beyond);
}

}  // namespace

bool allFinite(const Real* a, const Real* b, const std::size_t count) {
  return zeroProbe(a, b, count);
}

bool allFinite(const Real* a, const Real* b, const std::size_t count, const Real bound_squared,
               bool& beyond) {
  return zeroProbeWithBound(a, b, count, bound_squared, beyond);
}

}  // namespace engine
}  // namespace mass_aggregate_sim
