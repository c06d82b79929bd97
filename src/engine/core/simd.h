#pragma once
// Four doubles as one value (GCC and Clang vector extensions): element-wise IEEE arithmetic, so
// the results are the bits the scalar code gives. Where the CPU has no 256-bit registers the
// compiler splits each operation in two. MAS_SIMD_CLONES compiles a hot function twice on x86-64,
// for AVX2 and for the baseline, and picks one when the library loads; neither version contracts
// a * b + c into a fused multiply-add (the engine builds with -ffp-contract=off), so both give the
// same bits.

#include <cstdint>
#include <cstring>

#include "mass_aggregate_sim/engine/core/types.h"

// Not under AddressSanitizer: its run time is not ready when the loader picks a version.
#if defined(__SANITIZE_ADDRESS__)
#define MAS_SIMD_NO_CLONES
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define MAS_SIMD_NO_CLONES
#endif
#endif
#if defined(__x86_64__) && defined(__ELF__) && !defined(MAS_SIMD_NO_CLONES)
#define MAS_SIMD_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define MAS_SIMD_CLONES
#endif

namespace mass_aggregate_sim {
namespace engine {
namespace simd {

typedef Real Real4 __attribute__((vector_size(4 * sizeof(Real))));

inline Real4 load(const Real* p) {
  Real4 r;
  std::memcpy(&r, p, sizeof r);
  return r;
}

inline void store(Real* p, const Real4 value) { std::memcpy(p, &value, sizeof value); }

inline Real4 broadcast(const Real value) { return Real4{value, value, value, value}; }

// Lane masks from comparisons: all bits set where true.
typedef std::int64_t Mask4 __attribute__((vector_size(4 * sizeof(std::int64_t))));

inline Real4 select(const Mask4 mask, const Real4 if_set, const Real4 otherwise) {
  return (Real4)(((Mask4)if_set & mask) | ((Mask4)otherwise & ~mask));
}

inline bool allSet(const Mask4 mask) { return (mask[0] & mask[1] & mask[2] & mask[3]) == -1; }

// Four particles' xyz, twelve doubles, are three Real4: (x0 y0 z0 x1) (y1 z1 x2 y2) (z2 x3 y3 z3).
// spreadN gives the per-particle scalars s0..s3 lined up with the Nth of them.
inline Real4 spread0(const Real4 s) { return __builtin_shufflevector(s, s, 0, 0, 0, 1); }
inline Real4 spread1(const Real4 s) { return __builtin_shufflevector(s, s, 1, 1, 2, 2); }
inline Real4 spread2(const Real4 s) { return __builtin_shufflevector(s, s, 2, 3, 3, 3); }

inline Real4 spread(const Real4 s, const int part) {
  return part == 0 ? spread0(s) : part == 1 ? spread1(s) : spread2(s);
}

// A constant 3-vector c lined up the same way.
inline Real4 pattern0(const Real* c) { return Real4{c[0], c[1], c[2], c[0]}; }
inline Real4 pattern1(const Real* c) { return Real4{c[1], c[2], c[0], c[1]}; }
inline Real4 pattern2(const Real* c) { return Real4{c[2], c[0], c[1], c[2]}; }

}  // namespace simd
}  // namespace engine
}  // namespace mass_aggregate_sim
