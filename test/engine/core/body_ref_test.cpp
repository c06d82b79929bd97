// A constraint side names a body by kind and dense index; a particle's handle is its index itself,
// so particle rows index their arrays with it at no cost.
#include "engine/core/body_ref.h"

#include <gtest/gtest.h>

#include <cstring>

#include "engine/solver/constraint_row.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

TEST(BodyRef, AParticleHandleIsItsIndex) {
  for (const std::uint32_t index : {0u, 1u, 4096u, BodyRef::kMaxIndex}) {
    const BodyRef ref = BodyRef::particle(index);
    EXPECT_EQ(ref.kind(), BodyKind::kParticle);
    EXPECT_EQ(ref.index(), index);
    EXPECT_EQ(ref.particleIndex(), index);
    std::uint32_t bits = 0;
    std::memcpy(&bits, &ref, sizeof bits);
    EXPECT_EQ(bits, index);
  }
}

TEST(BodyRef, HandlesCompareByKindAndIndex) {
  EXPECT_EQ(BodyRef::particle(7), BodyRef(BodyKind::kParticle, 7));
  EXPECT_NE(BodyRef::particle(7), BodyRef::particle(8));
}

TEST(ConstraintRow, AParticleRowIsOneCacheLineWithoutAngularTerms) {
  EXPECT_EQ(sizeof(ParticleRow), 64u);
  EXPECT_EQ(alignof(ParticleRow), 64u);
  EXPECT_FALSE(ParticleRow::kTurns);
  ParticleRow row{};
  row.flags = RowFlags::kUnilateral;
  EXPECT_TRUE(row.unilateral());
  row.flags = RowFlags::kActive;
  EXPECT_FALSE(row.unilateral());
}

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
