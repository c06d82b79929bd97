// The impulses kept by key from one step to the next: added in any order, found by key after the
// sort, a key not kept found as none.
#include "engine/bodies/kept_impulses.h"

#include <gtest/gtest.h>

#include <cstdint>

namespace mass_aggregate_sim {
namespace engine {
namespace {

TEST(KeptImpulses, EachKeyFindsItsOwnImpulsesAfterTheSort) {
  KeptImpulses kept;
  kept.add(42, 1.5, -2.0);
  kept.add(7, 0.25, 0.0, Vec3(0.5, -0.5, 0.0));
  kept.add(std::uint64_t{3} << 62, 9.0, 1.0);
  kept.sortByKey();
  ASSERT_EQ(kept.entries().size(), 3u);
  EXPECT_EQ(kept.entries().front().key, 7u);
  const KeptImpulses::Entry* link = kept.find(42);
  ASSERT_NE(link, nullptr);
  EXPECT_EQ(link->lower, 1.5);
  EXPECT_EQ(link->upper, -2.0);
  const KeptImpulses::Entry* pair = kept.find(7);
  ASSERT_NE(pair, nullptr);
  EXPECT_EQ(pair->lower, 0.25);
  EXPECT_EQ(pair->upper, 0.0);
  EXPECT_EQ(pair->friction, Vec3(0.5, -0.5, 0.0));
  EXPECT_EQ(link->friction, Vec3::Zero());
  ASSERT_NE(kept.find(std::uint64_t{3} << 62), nullptr);
  EXPECT_EQ(kept.find(8), nullptr);
  EXPECT_EQ(kept.find(43), nullptr);
  kept.clear();
  EXPECT_EQ(kept.find(42), nullptr);
}

TEST(KeptImpulses, ASwapHandsOverTheEntries) {
  KeptImpulses kept;
  kept.add(1, 2.0);
  kept.sortByKey();
  KeptImpulses previous;
  previous.swap(kept);
  EXPECT_TRUE(kept.entries().empty());
  ASSERT_NE(previous.find(1), nullptr);
  EXPECT_EQ(previous.find(1)->lower, 2.0);
}

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
