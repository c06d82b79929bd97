// The slots of the contacts' kept inverted masses: taken by a contact of more than one point,
// zeroed when reused, given back when the contact ends, and left alone while it lasts.
#include "engine/bodies/kept_mass_pool.h"

#include <gtest/gtest.h>

#include <vector>

namespace mass_aggregate_sim {
namespace engine {
namespace {

BodyContact contactOf(const int points) {
  BodyContact c;
  c.manifold.count = points;
  return c;
}

TEST(KeptMassPool, OnlyAContactOfSeveralPointsTakesASlot) {
  KeptMassPool pool;
  BodyContact single = contactOf(1);
  pool.of(single).coupled.mass(0, 0) = 3.0;  // the shared scratch: nothing keeps it
  EXPECT_EQ(single.kept_masses, BodyContact::kNoKeptMasses);
  EXPECT_EQ(pool.taken(), 0u);
  EXPECT_EQ(static_cast<const KeptMassPool&>(pool).of(single).coupled.mass(0, 0), 0.0);
  BodyContact face = contactOf(4);
  pool.of(face).coupled.mass(1, 2) = 5.0;
  EXPECT_NE(face.kept_masses, BodyContact::kNoKeptMasses);
  EXPECT_EQ(pool.taken(), 1u);
  // The slot follows the contact through copies, and one point later keeps it.
  BodyContact copy = face;
  copy.manifold.count = 1;
  EXPECT_EQ(pool.of(copy).coupled.mass(1, 2), 5.0);
}

TEST(KeptMassPool, EndedContactsGiveTheirSlotsBackAndReusedSlotsStartAtZero) {
  KeptMassPool pool;
  std::vector<BodyContact> before;
  for (int k = 0; k < 5; ++k) {
    before.push_back(contactOf(k % 2 == 0 ? 4 : 1));
    pool.of(before.back()).upper_alone.inverse(0, 0) = 1.0 + k;
  }
  EXPECT_EQ(pool.taken(), 3u);
  // Contacts 0 and 2 end; 4 lasts.
  const std::vector<BodyContact> after = {before[1], before[4]};
  pool.keepOnly(before, after);
  EXPECT_EQ(pool.taken(), 1u);
  EXPECT_EQ(pool.of(after[1]).upper_alone.inverse(0, 0), 5.0);
  BodyContact fresh = contactOf(3);
  EXPECT_EQ(pool.of(fresh).upper_alone.inverse(0, 0), 0.0);
  EXPECT_NE(fresh.kept_masses, after[1].kept_masses);
  EXPECT_EQ(pool.taken(), 2u);
  pool.giveBack(fresh);
  EXPECT_EQ(pool.taken(), 1u);
}

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
