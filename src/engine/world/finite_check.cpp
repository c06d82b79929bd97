#include "engine/world/finite_check.h"

#include "engine/core/simd.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

// Inlined into the cloned function below: Clang refuses calls that pass or return 256-bit vectors
// written directly in the baseline version of a function.
inline __attribute__((always_inline)) bool sumsToZero(const Real* a, const Real* b,
                                                      const std::size_t count) {
  simd::Real4 sum = simd::broadcast(0.0);
  std::size_t k = 0;
  for (; k + 4 <= count; k += 4) sum += finiteProbeTerm(simd::load(a + k), simd::load(b + k));
  Real tail = 0.0;
  for (; k < count; ++k) tail += finiteProbeTerm(a[k], b[k]);
  return probedFinite(sum, tail);
}

MAS_SIMD_CLONES bool zeroProbe(const Real* a, const Real* b, const std::size_t count) {
  return sumsToZero(a, b, count);
}

}  // namespace

bool allFinite(const Real* a, const Real* b, const std::size_t count) {
  return zeroProbe(a, b, count);
}

}  // namespace engine
}  // namespace mass_aggregate_sim
