#include "engine/collision/broadphase.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "mass_aggregate_sim/engine/world/world.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

// Boxes of spheres with mixed radii spread over a region; some boxes stretched as by fast motion.
void randomBoxes(std::mt19937& rng, const int n, const Real region, const bool swept, Vec3Array& lo,
                 Vec3Array& hi) {
  std::uniform_real_distribution<Real> position(-region, region);
  std::uniform_real_distribution<Real> radius(0.01, 0.3);
  std::uniform_real_distribution<Real> motion(-3.0, 3.0);
  std::uniform_int_distribution<int> pick(0, 19);
  lo.resize(3, n);
  hi.resize(3, n);
  for (int i = 0; i < n; ++i) {
    const Vec3 centre(position(rng), position(rng), position(rng));
    const Vec3 r = Vec3::Constant(radius(rng));
    Vec3 end = centre;
    if (swept && pick(rng) == 0) end += Vec3(motion(rng), motion(rng), motion(rng));
    lo.col(i) = centre.cwiseMin(end) - r;
    hi.col(i) = centre.cwiseMax(end) + r;
  }
}

std::vector<IndexPair> sorted(std::vector<IndexPair> pairs) {
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

TEST(Broadphase, SortAndSweepAndGridFindExactlyTheBruteForcePairs) {
  std::mt19937 rng(7);
  BroadphaseFinder finder;
  std::vector<IndexPair> reference;
  std::vector<IndexPair> found;
  std::size_t total_pairs = 0;
  for (int scene = 0; scene < 40; ++scene) {
    const int n = 50 + 40 * scene;
    const Real region = 0.5 + 0.1 * scene;
    Vec3Array lo;
    Vec3Array hi;
    randomBoxes(rng, n, region, scene % 2 == 1, lo, hi);
    bruteForcePairs(lo, hi, reference);
    total_pairs += reference.size();
    for (const Broadphase method : {Broadphase::kSortAndSweep, Broadphase::kUniformGrid}) {
      finder.findPairs(method, lo, hi, found);
      ASSERT_EQ(found.size(), reference.size())
          << broadphaseName(method) << " scene " << scene << " (duplicates or misses)";
      ASSERT_EQ(sorted(found), reference) << broadphaseName(method) << " scene " << scene;
    }
  }
  EXPECT_GT(total_pairs, 1000u);  // the scenes are not trivially empty
}

TEST(Broadphase, TouchingBoxesAndDegenerateInputs) {
  BroadphaseFinder finder;
  std::vector<IndexPair> found;
  Vec3Array lo(3, 4);
  Vec3Array hi(3, 4);
  // 0 and 1 touch on a face (closed boxes overlap); 2 is far; 3 is not finite.
  lo.col(0) << 0, 0, 0;
  hi.col(0) << 1, 1, 1;
  lo.col(1) << 1, 0, 0;
  hi.col(1) << 2, 1, 1;
  lo.col(2) << 5, 5, 5;
  hi.col(2) << 6, 6, 6;
  lo.col(3) << std::numeric_limits<Real>::quiet_NaN(), 0, 0;
  hi.col(3) << 1, 1, 1;
  for (const Broadphase method : {Broadphase::kSortAndSweep, Broadphase::kUniformGrid}) {
    finder.findPairs(method, lo, hi, found);
    ASSERT_EQ(found.size(), 1u) << broadphaseName(method);
    EXPECT_EQ(found[0], (IndexPair{0, 1}));
  }
  finder.findPairs(Broadphase::kUniformGrid, lo.leftCols(1), hi.leftCols(1), found);
  EXPECT_TRUE(found.empty());
}

TEST(Broadphase, NamesRoundTrip) {
  for (const Broadphase method : {Broadphase::kSortAndSweep, Broadphase::kUniformGrid}) {
    EXPECT_EQ(parseBroadphase(broadphaseName(method)), method);
  }
  EXPECT_EQ(parseBroadphase("octree"), std::nullopt);
  EXPECT_EQ(broadphaseNames(), "sort_and_sweep, uniform_grid");
}

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
