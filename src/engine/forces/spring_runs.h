#pragma once

#include <cstdint>
#include <vector>

#include "mass_aggregate_sim/engine/core/particle_store.h"
#include "mass_aggregate_sim/engine/core/types.h"
#include "mass_aggregate_sim/engine/forces/spring.h"

namespace mass_aggregate_sim {
namespace engine {

// A spring between two particles with both ends as dense indices, a < b (the ends swapped when
// needed: the force on each end is then the same to the bit).
struct DenseSpring {
  std::uint32_t a = 0;
  std::uint32_t b = 0;
  Real stiffness = 0.0;
  Real rest_length = 0.0;
  Real damping = 0.0;
};

// An anchored spring with its particle as a dense index.
struct DenseAnchoredSpring {
  std::uint32_t a = 0;
  Vec3 anchor = Vec3::Zero();
  Real stiffness = 0.0;
  Real rest_length = 0.0;
  Real damping = 0.0;
};

// A list of pair springs cut, in order, into segments. A run is a segment whose ends advance
// together (spring first + j joins a + j and b + j): chains, ropes and the rows and columns of a
// cloth come out that way, and a run reads its positions and adds its forces as contiguous blocks,
// four springs at a time.
struct SpringSegment {
  std::uint32_t first = 0;
  std::uint32_t count = 0;
  bool run = false;
  bool damped = false;  // a spring of the segment has damping != 0
};

// The springs of a world with dense ends, in their order within each list: the hot loops read
// packed arrays instead of looking every id up. Valid while neither the springs nor the store's
// layout (ParticleStore::layoutVersion) change.
struct DenseSprings {
  std::vector<DenseSpring> pairs;
  std::vector<SpringSegment> pair_segments;
  std::vector<DenseAnchoredSpring> anchored;
  std::vector<DenseSpring> pull_pairs;  // bungees
  std::vector<SpringSegment> pull_pair_segments;
  std::vector<DenseAnchoredSpring> pull_anchored;
};
DenseSprings resolveDenseSprings(const std::vector<Spring>& springs,
                                 const ParticleStore& particles);

// Adds every spring's force at (x, v) to `force`; with `energy`, adds their elastic energy at x
// (from the lengths the force pass computes).
void accumulateDenseSprings(const DenseSprings& dense, const Eigen::Ref<const Vec3Array>& x,
                            const Eigen::Ref<const Vec3Array>& v, Eigen::Ref<Vec3Array> force,
                            Real* energy);
// Their elastic energy at x: k (l - L)^2 / 2 each (stretched ones only when pulling only).
Real denseSpringEnergy(const DenseSprings& dense, const ConstVec3Map& x);

}  // namespace engine
}  // namespace mass_aggregate_sim
