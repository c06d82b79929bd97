#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "mass_aggregate_sim/engine/world/world.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

// A box of five half-spaces (floor and four walls) with side 2 * half_width.
void addContainer(World& world, const Real half_width, const Material& material) {
  ASSERT_TRUE(world.addCollider(PlaneCollider{Vec3::UnitZ(), 0.0, material}).isOk());
  ASSERT_TRUE(world.addCollider(PlaneCollider{Vec3::UnitX(), -half_width, material}).isOk());
  ASSERT_TRUE(world.addCollider(PlaneCollider{-Vec3::UnitX(), -half_width, material}).isOk());
  ASSERT_TRUE(world.addCollider(PlaneCollider{Vec3::UnitY(), -half_width, material}).isOk());
  ASSERT_TRUE(world.addCollider(PlaneCollider{-Vec3::UnitY(), -half_width, material}).isOk());
}

class Pile : public ::testing::TestWithParam<Broadphase> {};

// 1,000 particles dropped into a box settle into a still pile. Bound: after settling, the total
// kinetic energy stays below 1e-4 J, i.e. an rms speed of 1.4 mm/s for 1,000 particles of 0.1 kg
// (the slowest speed of their fall in a single substep is g h = 0.16 m/s).
TEST_P(Pile, ThousandParticlesSettleAndStayStill) {
  WorldConfig config;
  config.gravity = Vec3(0.0, 0.0, -9.81);
  World world(config);
  CollisionSettings settings;
  settings.particle_collisions = true;
  settings.broadphase = GetParam();
  settings.particle_restitution = 0.2;
  settings.particle_friction = 0.3;
  ASSERT_TRUE(world.setCollisionSettings(settings).isOk());
  addContainer(world, 0.5, Material{0.2, 0.3});
  std::mt19937 rng(11);
  std::uniform_real_distribution<Real> jitter(-0.005, 0.005);
  const Real radius = 0.025;
  // A 10 x 10 x 10 lattice a little wider than the particles, falling in together.
  for (int i = 0; i < 10; ++i) {
    for (int j = 0; j < 10; ++j) {
      for (int k = 0; k < 10; ++k) {
        ParticleSpec spec;
        spec.position = Vec3(-0.4 + 0.09 * i + jitter(rng), -0.4 + 0.09 * j + jitter(rng),
                             0.1 + 0.06 * k + jitter(rng));
        spec.radius = radius;
        spec.inverse_mass = 10.0;
        ASSERT_TRUE(world.addParticle(spec).isOk());
      }
    }
  }
  ASSERT_EQ(world.particles().size(), 1000u);
  for (int s = 0; s < 240; ++s) world.step();
  Real worst_energy = 0.0;
  Real worst_penetration = 0.0;
  for (int s = 0; s < 60; ++s) {
    world.step();
    worst_energy = std::max(worst_energy, world.kineticEnergy());
    worst_penetration = std::max(worst_penetration, world.lastContactStats().max_penetration);
  }
  EXPECT_LT(worst_energy, 1e-4) << broadphaseName(GetParam());
  EXPECT_GT(world.lastContactStats().contacts, 1000u);
  EXPECT_EQ(world.lastContactStats().dropped, 0u);
  // Nothing escaped the box or sank through the floor.
  const auto x = world.particles().positions();
  EXPECT_GT(x.row(2).minCoeff(), radius - 0.01);
  EXPECT_LT(x.row(0).cwiseAbs().maxCoeff(), 0.5 - radius + 0.01);
  EXPECT_LT(x.row(1).cwiseAbs().maxCoeff(), 0.5 - radius + 0.01);
  EXPECT_LT(worst_penetration, 0.01);
}

INSTANTIATE_TEST_SUITE_P(BothBroadphases, Pile,
                         ::testing::Values(Broadphase::kSortAndSweep, Broadphase::kUniformGrid),
                         [](const ::testing::TestParamInfo<Broadphase>& info) {
                           return std::string(broadphaseName(info.param));
                         });

constexpr Real kGrainRadius = 0.05;
constexpr Real kStrikeSpeed = 5.0;

// A column of `grains` grains (5 cm, 50 g) resting on the ground, settled for a second, and one
// more 5 cm above the top falling at 5 m/s (the last particle), all of the given restitution;
// `rested`: the column's heights before the strike.
World struckColumn(const int grains, const Real restitution, std::vector<Real>& rested) {
  WorldConfig config;
  config.gravity = Vec3(0.0, 0.0, -9.81);
  World world(config);
  CollisionSettings settings;
  settings.particle_collisions = true;
  settings.particle_restitution = restitution;
  EXPECT_TRUE(world.setCollisionSettings(settings).isOk());
  EXPECT_TRUE(world.addCollider(PlaneCollider{Vec3::UnitZ(), 0.0, Material{0.0, 0.5}}).isOk());
  ParticleSpec spec;
  spec.radius = kGrainRadius;
  spec.inverse_mass = 20.0;
  for (int k = 0; k < grains; ++k) {
    spec.position = Vec3(0.0, 0.0, kGrainRadius * (1 + 2 * k));
    EXPECT_TRUE(world.addParticle(spec).isOk());
  }
  for (int step = 0; step < 60; ++step) world.step();
  rested.clear();
  for (int k = 0; k < grains; ++k) rested.push_back(world.particles().positions()(2, k));
  spec.position = Vec3(0.0, 0.0, kGrainRadius * (1 + 2 * grains) + 0.05);
  spec.velocity = Vec3(0.0, 0.0, -kStrikeSpeed);
  EXPECT_TRUE(world.addParticle(spec).isOk());
  return world;
}

// How far the column's grains rose above where they rested, at most, over `steps` frames; and
// the striker's fastest rise.
void watchStrike(World& world, const std::vector<Real>& rested, const int steps, Real& rose,
                 Real& rebound) {
  rose = 0.0;
  rebound = 0.0;
  const auto striker = static_cast<Eigen::Index>(rested.size());
  for (int step = 0; step < steps; ++step) {
    world.step();
    for (std::size_t k = 0; k < rested.size(); ++k) {
      rose = std::max(rose,
                      world.particles().positions()(2, static_cast<Eigen::Index>(k)) - rested[k]);
    }
    rebound = std::max(rebound, world.particles().velocities()(2, striker));
  }
}

// A grain resting on the ground struck from above at 5 m/s stays on the ground, and the other
// bounces off it as off the ground. The struck grain followed only its ground contact's impulse,
// which took back the blow from above as well as its weight: it rose 2.9 cm (restitution 0) and
// 6.2 cm (0.8), floating up and falling back for seven frames.
TEST(Pile, AGrainStruckFromAboveStaysOnTheGround) {
  for (const Real restitution : {0.0, 0.8}) {
    std::vector<Real> rested;
    World world = struckColumn(1, restitution, rested);
    Real rose = 0.0;
    Real rebound = 0.0;
    watchStrike(world, rested, 30, rose, rebound);
    EXPECT_LT(rose, 1e-3) << "restitution " << restitution;
    EXPECT_NEAR(rebound, restitution * kStrikeSpeed, 0.02 * kStrikeSpeed)
        << "restitution " << restitution;
  }
}

// The same through a column of three grains: each stays where it rested (the top one rose 2.5
// cm at restitution 0 and 5.6 cm at 0.8, the middle one 0.7 cm).
TEST(Pile, AColumnStruckFromAboveStaysInPlace) {
  for (const Real restitution : {0.0, 0.8}) {
    std::vector<Real> rested;
    World world = struckColumn(3, restitution, rested);
    Real rose = 0.0;
    Real rebound = 0.0;
    watchStrike(world, rested, 60, rose, rebound);
    EXPECT_LT(rose, 1e-3) << "restitution " << restitution;
  }
}

TEST(ContactBuffer, DropsBeyondTheLimitAndCountsThem) {
  World world;
  CollisionSettings settings;
  settings.particle_collisions = true;
  settings.max_contacts = 3;
  ASSERT_TRUE(world.setCollisionSettings(settings).isOk());
  // Six particles in a row, each overlapping the next: five contacts, three kept.
  for (int i = 0; i < 6; ++i) {
    ParticleSpec spec;
    spec.position = Vec3(0.15 * i, 0, 0);
    spec.radius = 0.1;
    ASSERT_TRUE(world.addParticle(spec).isOk());
  }
  world.step();
  EXPECT_EQ(world.lastContactStats().contacts, 3u);
  EXPECT_EQ(world.lastContactStats().dropped, 2u);
  settings.max_contacts = 0;  // grows as needed
  ASSERT_TRUE(world.setCollisionSettings(settings).isOk());
  world.step();
  EXPECT_EQ(world.lastContactStats().dropped, 0u);
}

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
