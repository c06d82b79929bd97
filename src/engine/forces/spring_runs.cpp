// The springs' hot loops: the dense layout (ends as dense indices, runs of advancing ends) and
// the passes over it, scalar and four springs at a time (simd.h), with the same operations in the
// same order so both give the same bits.
#include "engine/forces/spring_runs.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "engine/core/simd.h"
#include "engine/forces/force_laws.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

// Pointer to column i of a 3 x N array that may have an outer stride.
template <typename Array>
inline auto column(Array& array, const std::size_t i) {
  return array.data() + static_cast<Eigen::Index>(i) * array.outerStride();
}

// Dense springs a block at a time: gather d = x_a - x_b, then l = sqrt(d.d) and 1/l for the
// whole block with Eigen's packet operations (IEEE sqrt and division, the same bits as the scalar
// ones, several per instruction), then the forces.
constexpr Eigen::Index kBlock = 64;
using BlockArray = Eigen::Array<Real, kBlock, 1>;

template <typename Positions>
inline void gatherBlock(const DenseSpring* block, const Eigen::Index m, const Positions& x,
                        Real (*d)[3], BlockArray& squared) {
  for (Eigen::Index j = 0; j < m; ++j) {
    const Real* const xa = column(x, block[j].a);
    const Real* const xb = column(x, block[j].b);
    Real* const dj = d[j];
    dj[0] = xa[0] - xb[0];
    dj[1] = xa[1] - xb[1];
    dj[2] = xa[2] - xb[2];
    squared[j] = dj[0] * dj[0] + dj[1] * dj[1] + dj[2] * dj[2];
  }
}

// With `energy`, adds k (l - L)^2 / 2 of each spring of the block (stretched ones only when
// pull_only) to it, in order.
inline void addBlockEnergy(const DenseSpring* block, const Eigen::Index m, const BlockArray& length,
                           const bool pull_only, Real* energy) {
  if (!energy) return;
  for (Eigen::Index j = 0; j < m; ++j) {
    const Real extension = length[j] - block[j].rest_length;
    if (pull_only && extension <= 0.0) continue;
    *energy += 0.5 * block[j].stiffness * extension * extension;
  }
}

// Springs in any order, a block at a time.
void accumulateScatteredBlocks(const DenseSpring* springs, const Eigen::Index count,
                               const Eigen::Ref<const Vec3Array>& x,
                               const Eigen::Ref<const Vec3Array>& v, const bool pull_only,
                               Eigen::Ref<Vec3Array> force, Real* energy) {
  Real d[kBlock][3];
  BlockArray squared;
  BlockArray length;
  BlockArray inverse_length;
  for (Eigen::Index start = 0; start < count; start += kBlock) {
    const Eigen::Index m = std::min(kBlock, count - start);
    const DenseSpring* const block = springs + start;
    gatherBlock(block, m, x, d, squared);
    length.head(m) = squared.head(m).sqrt();
    inverse_length.head(m) = length.head(m).inverse();
    addBlockEnergy(block, m, length, pull_only, energy);
    for (Eigen::Index j = 0; j < m; ++j) {
      const DenseSpring& s = block[j];
      Real f[3];
      if (!springForceFromLength(d[j], length[j], inverse_length[j], column(v, s.a), column(v, s.b),
                                 s.stiffness, s.rest_length, s.damping, pull_only, f)) {
        continue;
      }
      Real* const fa = column(force, s.a);
      Real* const fb = column(force, s.b);
      for (int c = 0; c < 3; ++c) {
        fa[c] += f[c];
        fb[c] -= f[c];
      }
    }
  }
}

// Four springs of a run, j..j+3, from their twelve position differences d (three Real4 in the
// layout of simd.h): f, the force on their a ends, in the same layout, by the operations of
// springForceFromLength in the same order; adds 1/2 k (l - L)^2 to `energy` lanes and clears the
// lanes of `exerts` for springs that exert nothing (slack bungee, coincident ends).
template <bool kPullOnly, bool kDamped>
inline __attribute__((always_inline)) void runGroupForces(const DenseSpring* s,
                                                          const simd::Real4* d,
                                                          const simd::Real4* dv, simd::Real4* f,
                                                          simd::Real4& energy,
                                                          simd::Mask4& exerts) {
  using simd::Real4;
  const Real4 sq[3] = {d[0] * d[0], d[1] * d[1], d[2] * d[2]};
  // Per spring (d_x^2 + d_y^2) + d_z^2, the components regrouped out of the interleaved lanes.
  const Real4 xy = __builtin_shufflevector(sq[0], sq[1], 0, 3, 6, 1);
  const Real4 squared_x = __builtin_shufflevector(xy, sq[2], 0, 1, 2, 5);
  const Real4 squared_y =
      __builtin_shufflevector(__builtin_shufflevector(sq[0], sq[1], 1, 4, 7, 0), sq[2], 0, 1, 2, 6);
  const Real4 squared_z =
      __builtin_shufflevector(__builtin_shufflevector(sq[0], sq[1], 2, 5, 0, 0), sq[2], 0, 1, 4, 7);
  const Real4 squared = (squared_x + squared_y) + squared_z;
  const Real4 length = {std::sqrt(squared[0]), std::sqrt(squared[1]), std::sqrt(squared[2]),
                        std::sqrt(squared[3])};
  const Real4 inverse_length = 1.0 / length;
  const Real4 rest = {s[0].rest_length, s[1].rest_length, s[2].rest_length, s[3].rest_length};
  const Real4 stiffness = {s[0].stiffness, s[1].stiffness, s[2].stiffness, s[3].stiffness};
  const Real4 extension = length - rest;
  const auto long_enough = (simd::Mask4)(length >= simd::broadcast(kMinSpringLength));
  if constexpr (kPullOnly) {
    const auto taut = (simd::Mask4)(extension > simd::broadcast(0.0));
    exerts &= long_enough & taut;
    energy += simd::select(taut, (0.5 * stiffness) * extension * extension, simd::broadcast(0.0));
  } else {
    exerts &= long_enough;
    energy += (0.5 * stiffness) * extension * extension;
  }
  Real4 n[3];
  for (int b = 0; b < 3; ++b) n[b] = d[b] * simd::spread(inverse_length, b);
  Real4 damping_force = simd::broadcast(0.0);
  if constexpr (kDamped) {
    const Real4 c = {s[0].damping, s[1].damping, s[2].damping, s[3].damping};
    // (dv . n) per spring, regrouped as the squares were
    const Real4 p[3] = {dv[0] * n[0], dv[1] * n[1], dv[2] * n[2]};
    const Real4 px =
        __builtin_shufflevector(__builtin_shufflevector(p[0], p[1], 0, 3, 6, 1), p[2], 0, 1, 2, 5);
    const Real4 py =
        __builtin_shufflevector(__builtin_shufflevector(p[0], p[1], 1, 4, 7, 0), p[2], 0, 1, 2, 6);
    const Real4 pz =
        __builtin_shufflevector(__builtin_shufflevector(p[0], p[1], 2, 5, 0, 0), p[2], 0, 1, 4, 7);
    // c != 0 ? c (dv . n) : 0, as the scalar loop skips undamped springs
    damping_force = simd::select((simd::Mask4)(c != simd::broadcast(0.0)), c * ((px + py) + pz),
                                 simd::broadcast(0.0));
  }
  const Real4 magnitude = -(stiffness * extension + damping_force);
  for (int b = 0; b < 3; ++b) f[b] = simd::spread(magnitude, b) * n[b];
}

// A run (spring j joins a0 + j and b0 + j, b0 > a0) on contiguous arrays, a block at a time. The
// forces are added as two contiguous sweeps, the b ends first: a particle that is the b end of
// spring j - (b0 - a0) and the a end of spring j gets the earlier spring's force first, as the
// spring-by-spring loop gives it, so the sums are the same to the bit. A block with a spring that
// exerts nothing adds its forces spring by spring. Elastic energy is summed in four lanes.
template <bool kPullOnly, bool kDamped>
inline __attribute__((always_inline)) void runBlocks(const DenseSpring* springs,
                                                     const Eigen::Index count, const Real* x,
                                                     const Real* v, Real* force, Real* energy) {
  using simd::load;
  using simd::Real4;
  Real f[3 * kBlock];
  Real4 energy_lanes = simd::broadcast(0.0);
  Real tail_energy = 0.0;
  for (Eigen::Index start = 0; start < count; start += kBlock) {
    const Eigen::Index m = std::min(kBlock, count - start);
    const DenseSpring* const block = springs + start;
    const std::size_t a0 = 3 * std::size_t{block[0].a};
    const std::size_t b0 = 3 * std::size_t{block[0].b};
    simd::Mask4 exerts = ~simd::Mask4{};
    Eigen::Index j = 0;
    for (; j + 4 <= m; j += 4) {
      const std::size_t k = 3 * static_cast<std::size_t>(j);
      Real4 d[3];
      Real4 dv[3];
      for (int b = 0; b < 3; ++b) {
        d[b] = load(x + a0 + k + 4 * b) - load(x + b0 + k + 4 * b);
        if constexpr (kDamped) dv[b] = load(v + a0 + k + 4 * b) - load(v + b0 + k + 4 * b);
      }
      Real4 group_f[3];
      runGroupForces<kPullOnly, kDamped>(block + j, d, dv, group_f, energy_lanes, exerts);
      for (int b = 0; b < 3; ++b) simd::store(f + k + 4 * b, group_f[b]);
    }
    bool exerts_all = simd::allSet(exerts);
    for (; j < m; ++j) {
      const std::size_t k = 3 * static_cast<std::size_t>(j);
      const Real d[3] = {x[a0 + k] - x[b0 + k], x[a0 + k + 1] - x[b0 + k + 1],
                         x[a0 + k + 2] - x[b0 + k + 2]};
      const Real length = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      const Real extension = length - block[j].rest_length;
      if (!(kPullOnly && extension <= 0.0)) {
        tail_energy += 0.5 * block[j].stiffness * extension * extension;
      }
      if (!springForceFromLength(d, length, 1.0 / length, v + a0 + k, v + b0 + k,
                                 block[j].stiffness, block[j].rest_length, block[j].damping,
                                 kPullOnly, f + k)) {
        exerts_all = false;
      }
    }
    const Eigen::Index components = 3 * m;
    if (exerts_all) {
      Real* const fb = force + b0;
      for (Eigen::Index c = 0; c < components; ++c) fb[c] -= f[c];
      Real* const fa = force + a0;
      for (Eigen::Index c = 0; c < components; ++c) fa[c] += f[c];
      continue;
    }
    for (j = 0; j < m; ++j) {
      const std::size_t k = 3 * static_cast<std::size_t>(j);
      const Real d[3] = {x[a0 + k] - x[b0 + k], x[a0 + k + 1] - x[b0 + k + 1],
                         x[a0 + k + 2] - x[b0 + k + 2]};
      const Real length = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      if (length < kMinSpringLength || (kPullOnly && length - block[j].rest_length <= 0.0))
        continue;
      for (int c = 0; c < 3; ++c) {
        force[a0 + k + c] += f[k + c];
        force[b0 + k + c] -= f[k + c];
      }
    }
  }
  if (energy) {
    *energy +=
        (((energy_lanes[0] + energy_lanes[1]) + energy_lanes[2]) + energy_lanes[3]) + tail_energy;
  }
}

MAS_SIMD_CLONES void accumulateRunBlocks(const DenseSpring* springs, const Eigen::Index count,
                                         const Real* x, const Real* v, const bool pull_only,
                                         const bool damped, Real* force, Real* energy) {
  if (pull_only) {
    damped ? runBlocks<true, true>(springs, count, x, v, force, energy)
           : runBlocks<true, false>(springs, count, x, v, force, energy);
  } else {
    damped ? runBlocks<false, true>(springs, count, x, v, force, energy)
           : runBlocks<false, false>(springs, count, x, v, force, energy);
  }
}

void accumulateDensePairForces(const std::vector<DenseSpring>& springs,
                               const std::vector<SpringSegment>& segments,
                               const Eigen::Ref<const Vec3Array>& x,
                               const Eigen::Ref<const Vec3Array>& v, const bool pull_only,
                               Eigen::Ref<Vec3Array> force, Real* energy) {
  const bool contiguous = x.outerStride() == 3 && v.outerStride() == 3 && force.outerStride() == 3;
  for (const SpringSegment& segment : segments) {
    const DenseSpring* const first = springs.data() + segment.first;
    const auto count = static_cast<Eigen::Index>(segment.count);
    if (segment.run && contiguous) {
      accumulateRunBlocks(first, count, x.data(), v.data(), pull_only, segment.damped, force.data(),
                          energy);
    } else {
      accumulateScatteredBlocks(first, count, x, v, pull_only, force, energy);
    }
  }
}

// energy + sum k (l - L)^2 / 2 over dense springs (stretched ones only when pull_only), summed in
// order.
Real addDensePairEnergy(Real energy, const std::vector<DenseSpring>& springs, const ConstVec3Map& x,
                        const bool pull_only) {
  Real d[kBlock][3];
  BlockArray squared;
  BlockArray length;
  const auto count = static_cast<Eigen::Index>(springs.size());
  for (Eigen::Index start = 0; start < count; start += kBlock) {
    const Eigen::Index m = std::min(kBlock, count - start);
    const DenseSpring* const block = springs.data() + start;
    gatherBlock(block, m, x, d, squared);
    length.head(m) = squared.head(m).sqrt();
    for (Eigen::Index j = 0; j < m; ++j) {
      const Real extension = length[j] - block[j].rest_length;
      if (pull_only && extension <= 0.0) continue;
      energy += 0.5 * block[j].stiffness * extension * extension;
    }
  }
  return energy;
}

// Anchored springs one by one (an anchor's velocity is zero); with `energy`, adds k (l - L)^2 / 2
// of each (stretched ones only when pull_only) to it.
void accumulateAnchoredForces(const std::vector<DenseAnchoredSpring>& springs,
                              const Eigen::Ref<const Vec3Array>& x,
                              const Eigen::Ref<const Vec3Array>& v, const bool pull_only,
                              Eigen::Ref<Vec3Array> force, Real* energy) {
  const Real at_rest[3] = {0.0, 0.0, 0.0};
  for (const DenseAnchoredSpring& spring : springs) {
    const std::size_t i = spring.a;
    if (energy) {
      const Real extension = (x.col(i) - spring.anchor).norm() - spring.rest_length;
      if (!(pull_only && extension <= 0.0)) {
        *energy += 0.5 * spring.stiffness * extension * extension;
      }
    }
    Real f[3];
    if (!springForce(column(x, i), spring.anchor.data(), column(v, i), at_rest, spring.stiffness,
                     spring.rest_length, spring.damping, pull_only, f)) {
      continue;
    }
    Real* const fi = column(force, i);
    for (int c = 0; c < 3; ++c) fi[c] += f[c];
  }
}

Real anchoredEnergy(const std::vector<DenseAnchoredSpring>& springs, const ConstVec3Map& x,
                    const bool pull_only) {
  Real energy = 0.0;
  for (const DenseAnchoredSpring& s : springs) {
    const Real extension = (x.col(s.a) - s.anchor).norm() - s.rest_length;
    if (pull_only && extension <= 0.0) continue;
    energy += 0.5 * s.stiffness * extension * extension;
  }
  return energy;
}

// Shorter stretches of advancing ends are not worth a run of their own.
constexpr std::uint32_t kMinRun = 8;

// Cuts springs into maximal runs of at least kMinRun and the scattered segments between them.
std::vector<SpringSegment> segmentSprings(const std::vector<DenseSpring>& springs) {
  std::vector<SpringSegment> segments;
  const auto add = [&segments](const std::uint32_t first, const std::uint32_t count,
                               const bool run) {
    if (count == 0) return;
    if (!run && !segments.empty() && !segments.back().run) {
      segments.back().count += count;
      return;
    }
    segments.push_back(SpringSegment{first, count, run});
  };
  const auto total = static_cast<std::uint32_t>(springs.size());
  std::uint32_t start = 0;
  while (start < total) {
    std::uint32_t end = start + 1;
    while (end < total && springs[end].a == springs[end - 1].a + 1 &&
           springs[end].b == springs[end - 1].b + 1) {
      ++end;
    }
    const bool run = end - start >= kMinRun;
    add(start, end - start, run);
    for (std::uint32_t j = start; j < end; ++j) {
      segments.back().damped = segments.back().damped || springs[j].damping != 0.0;
    }
    start = end;
  }
  return segments;
}

}  // namespace

DenseSprings resolveDenseSprings(const std::vector<Spring>& springs,
                                 const ParticleStore& particles) {
  DenseSprings dense;
  for (const Spring& spring : springs) {
    const auto a = static_cast<std::uint32_t>(particles.denseIndexUnchecked(spring.a));
    if (spring.anchored()) {
      (spring.pull_only ? dense.pull_anchored : dense.anchored)
          .push_back(DenseAnchoredSpring{a, spring.anchor, spring.stiffness, spring.rest_length,
                                         spring.damping});
      continue;
    }
    auto b = static_cast<std::uint32_t>(particles.denseIndexUnchecked(spring.b));
    auto first = a;
    // Swapping the ends negates d, n and f exactly, so each end gets the same force.
    if (first > b) std::swap(first, b);
    (spring.pull_only ? dense.pull_pairs : dense.pairs)
        .push_back(DenseSpring{first, b, spring.stiffness, spring.rest_length, spring.damping});
  }
  dense.pair_segments = segmentSprings(dense.pairs);
  dense.pull_pair_segments = segmentSprings(dense.pull_pairs);
  return dense;
}

void accumulateDenseSprings(const DenseSprings& dense, const Eigen::Ref<const Vec3Array>& x,
                            const Eigen::Ref<const Vec3Array>& v, Eigen::Ref<Vec3Array> force,
                            Real* energy) {
  // Pairs, anchored, then the same pulling only: the order of their sums (and so their bits).
  accumulateDensePairForces(dense.pairs, dense.pair_segments, x, v, false, force, energy);
  accumulateAnchoredForces(dense.anchored, x, v, false, force, energy);
  accumulateDensePairForces(dense.pull_pairs, dense.pull_pair_segments, x, v, true, force, energy);
  accumulateAnchoredForces(dense.pull_anchored, x, v, true, force, energy);
}

Real denseSpringEnergy(const DenseSprings& dense, const ConstVec3Map& x) {
  Real energy = addDensePairEnergy(0.0, dense.pairs, x, false);
  energy += anchoredEnergy(dense.anchored, x, false);
  energy = addDensePairEnergy(energy, dense.pull_pairs, x, true);
  return energy + anchoredEnergy(dense.pull_anchored, x, true);
}

}  // namespace engine
}  // namespace mass_aggregate_sim
