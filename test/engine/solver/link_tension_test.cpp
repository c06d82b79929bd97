#include <gtest/gtest.h>

#include <vector>

#include "mass_aggregate_sim/engine/world/world.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

constexpr Real kGravity = 9.81;
constexpr Real kMass = 2.0;
// After settling, the tension of a resting load is m g to within 0.5 %.
constexpr Real kRelativeTolerance = 5e-3;

World gravityWorld(const int substeps = 4) {
  WorldConfig config;
  config.gravity = Vec3(0.0, 0.0, -kGravity);
  config.substeps = substeps;
  return World(config);
}

ParticleId addAt(World& world, const Vec3& position, const Real mass = kMass) {
  ParticleSpec spec;
  spec.position = position;
  spec.inverse_mass = mass > 0.0 ? 1.0 / mass : 0.0;
  spec.radius = 0.05;
  return *world.addParticle(spec);
}

Real tensionOf(const World& world, const GeneratorId id) {
  for (const LinkTension& t : world.linkTensions()) {
    if (t.id == id) return t.tension;
  }
  ADD_FAILURE() << "link " << id << " not listed";
  return 0.0;
}

void settle(World& world, const int steps = 120) {
  for (int s = 0; s < steps; ++s) world.step();
}

TEST(LinkTension, EmptyBeforeAnyLinkAndZeroBeforeTheFirstStep) {
  World world = gravityWorld();
  EXPECT_TRUE(world.linkTensions().empty());
  const ParticleId bob = addAt(world, Vec3(0.0, 0.0, -1.0));
  const GeneratorId id = *world.addLink(Cable::anchoredAt(bob, Vec3::Zero(), 1.0, 0.0));
  const std::vector<LinkTension> tensions = world.linkTensions();
  ASSERT_EQ(tensions.size(), 1u);
  EXPECT_EQ(tensions[0].id, id);
  EXPECT_EQ(tensions[0].tension, 0.0);
}

TEST(LinkTension, HangingFromAnAnchoredCableCarriesItsWeight) {
  for (const int substeps : {1, 4}) {
    World world = gravityWorld(substeps);
    const ParticleId bob = addAt(world, Vec3(0.0, 0.0, -1.0));
    const GeneratorId id = *world.addLink(Cable::anchoredAt(bob, Vec3::Zero(), 1.0, 0.0));
    settle(world);
    EXPECT_NEAR(tensionOf(world, id), kMass * kGravity, kRelativeTolerance * kMass * kGravity)
        << substeps << " substeps";
  }
}

TEST(LinkTension, HangingFromAnAnchoredRodCarriesItsWeight) {
  World world = gravityWorld();
  const ParticleId bob = addAt(world, Vec3(0.0, 0.0, -1.5));
  const GeneratorId id = *world.addLink(Rod::anchoredAt(bob, Vec3::Zero(), 1.5));
  settle(world);
  EXPECT_NEAR(tensionOf(world, id), kMass * kGravity, kRelativeTolerance * kMass * kGravity);
}

TEST(LinkTension, CableAndRodBetweenParticlesCarryTheWeightBelowThem) {
  // An immovable particle holds a chain: cable to the first bob, rod from it to the second. The
  // cable carries both bobs, the rod only the lower one; the order of a and b does not matter.
  World world = gravityWorld();
  const ParticleId top = addAt(world, Vec3::Zero(), 0.0);
  const ParticleId upper = addAt(world, Vec3(0.0, 0.0, -1.0));
  const ParticleId lower = addAt(world, Vec3(0.0, 0.0, -2.0), 3.0);
  const GeneratorId cable = *world.addLink(Cable::between(top, upper, 1.0, 0.0));
  const GeneratorId rod = *world.addLink(Rod::between(lower, upper, 1.0));
  settle(world);
  const Real both = (kMass + 3.0) * kGravity;
  const Real lower_weight = 3.0 * kGravity;
  EXPECT_NEAR(tensionOf(world, cable), both, kRelativeTolerance * both);
  EXPECT_NEAR(tensionOf(world, rod), lower_weight, kRelativeTolerance * lower_weight);
}

TEST(LinkTension, RodHoldingAParticleUpIsInCompression) {
  // The particle rests on top of a rod anchored below it: the rod pushes, so its tension is -m g.
  World world = gravityWorld();
  const ParticleId top = addAt(world, Vec3(0.0, 0.0, 1.0));
  const GeneratorId id = *world.addLink(Rod::anchoredAt(top, Vec3::Zero(), 1.0));
  settle(world);
  EXPECT_NEAR(tensionOf(world, id), -kMass * kGravity, kRelativeTolerance * kMass * kGravity);
  EXPECT_NEAR(world.particles().positions().col(*world.particles().find(top)).z(), 1.0, 1e-6);
}

TEST(LinkTension, SlackCableReadsZero) {
  World world = gravityWorld();
  // The bob, 0.5 m below the anchor of a 1 m cable, rests on a rod standing on a second anchor.
  const ParticleId bob = addAt(world, Vec3(0.0, 0.0, -0.5));
  const GeneratorId cable = *world.addLink(Cable::anchoredAt(bob, Vec3::Zero(), 1.0, 0.0));
  const GeneratorId rod = *world.addLink(Rod::anchoredAt(bob, Vec3(0.0, 0.0, -1.5), 1.0));
  settle(world);
  EXPECT_EQ(tensionOf(world, cable), 0.0);
  EXPECT_NEAR(tensionOf(world, rod), -kMass * kGravity, kRelativeTolerance * kMass * kGravity);
}

TEST(LinkTension, RemovedLinksDisappearAndTheRestStaySortedById) {
  World world = gravityWorld();
  const ParticleId bob = addAt(world, Vec3(0.0, 0.0, -1.0));
  const ParticleId other = addAt(world, Vec3(1.0, 0.0, -1.0));
  // Kinds added out of the order linkTensions() visits them in, so sorting is needed.
  const GeneratorId rod = *world.addLink(Rod::anchoredAt(other, Vec3(1.0, 0.0, 0.0), 1.0));
  const GeneratorId cable = *world.addLink(Cable::anchoredAt(bob, Vec3::Zero(), 1.0, 0.0));
  const GeneratorId pair = *world.addLink(Cable::between(bob, other, 5.0, 0.0));
  settle(world, 30);
  std::vector<LinkTension> tensions = world.linkTensions();
  ASSERT_EQ(tensions.size(), 3u);
  EXPECT_EQ(tensions[0].id, rod);
  EXPECT_EQ(tensions[1].id, cable);
  EXPECT_EQ(tensions[2].id, pair);
  EXPECT_GT(tensions[0].tension, 0.0);
  EXPECT_GT(tensions[1].tension, 0.0);
  EXPECT_EQ(tensions[2].tension, 0.0);  // 1 m apart on a 5 m cable

  ASSERT_TRUE(world.removeGenerator(cable).isOk());
  tensions = world.linkTensions();
  ASSERT_EQ(tensions.size(), 2u);
  EXPECT_EQ(tensions[0].id, rod);
  EXPECT_EQ(tensions[1].id, pair);

  ASSERT_TRUE(world.removeParticle(other).isOk());  // takes the rod and the pair cable with it
  EXPECT_TRUE(world.linkTensions().empty());
}

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
