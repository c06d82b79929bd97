#include <gtest/gtest.h>

#include <cmath>

#include "../integrators/integrator_params.h"
#include "mass_aggregate_sim/engine/world/world.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

constexpr Real kGravity = 9.81;

World groundWorld(const Material& ground, const int substeps = 1) {
  WorldConfig config;
  config.gravity = Vec3(0, 0, -kGravity);
  config.substeps = substeps;
  World world(config);
  EXPECT_TRUE(world.addCollider(PlaneCollider{Vec3::UnitZ(), 0.0, ground}).isOk());
  return world;
}

ParticleId addBall(World& world, const Vec3& position, const Vec3& velocity = Vec3::Zero()) {
  ParticleSpec spec;
  spec.position = position;
  spec.velocity = velocity;
  spec.radius = 0.1;
  return *world.addParticle(spec);
}

TEST(Friction, SlidingParticleDeceleratesAtMuG) {
  const Real mu = 0.4;
  World world = groundWorld(Material{0.0, mu});
  addBall(world, Vec3(0, 0, 0.1), Vec3(3.0, 0, 0));
  // Coulomb: a = -mu g while sliding, so it stops after v^2 / (2 mu g) = 1.147 m.
  Real previous = 3.0;
  for (int s = 0; s < 30; ++s) {
    world.step();
    const Real v = world.particles().velocities()(0, 0);
    EXPECT_NEAR(previous - v, mu * kGravity * world.config().dt, 1e-9) << "step " << s;
    previous = v;
  }
  for (int s = 0; s < 120; ++s) world.step();
  EXPECT_NEAR(world.particles().velocities().col(0).norm(), 0.0, 1e-9);
  EXPECT_NEAR(world.particles().positions()(0, 0), 3.0 * 3.0 / (2 * mu * kGravity), 0.03);
}

TEST(Friction, HoldsOnASlopeBelowTheFrictionAngleAndSlidesAbove) {
  for (const Real degrees : {15.0, 30.0}) {
    const Real angle = degrees * M_PI / 180.0;
    const Real mu = 0.4;  // friction angle atan(0.4) = 21.8 degrees
    World world = groundWorld(Material{0.0, 0.0});
    ASSERT_TRUE(world.removeCollider(world.colliders().of<PlaneCollider>()[0].id).isOk());
    const Vec3 normal(-std::sin(angle), 0, std::cos(angle));
    ASSERT_TRUE(world.addCollider(PlaneCollider{normal, 0.0, Material{0.0, mu}}).isOk());
    addBall(world, 0.1 * normal);
    for (int s = 0; s < 120; ++s) world.step();
    const Real speed = world.particles().velocities().col(0).norm();
    if (degrees < 20.0) {
      EXPECT_LT(speed, 1e-9) << degrees;
    } else {
      // a = g (sin - mu cos) down the slope after 2 s.
      EXPECT_NEAR(speed, kGravity * (std::sin(angle) - mu * std::cos(angle)) * 2.0, 0.02);
    }
  }
}

class RestsAtOneSubstep : public ::testing::TestWithParam<Integrator> {};

TEST_P(RestsAtOneSubstep, BallComesToRest) {
  World world = groundWorld(Material{0.5, 0.0});
  WorldConfig config = world.config();
  config.integrator = GetParam();
  ASSERT_TRUE(world.setConfig(config).isOk());
  addBall(world, Vec3(0, 0, 1.1));
  for (int s = 0; s < 600; ++s) world.step();
  for (int s = 0; s < 60; ++s) {
    world.step();
    ASSERT_LT(world.particles().velocities().col(0).norm(), 1e-6);
    ASSERT_LE(0.1 - world.particles().positions()(2, 0),
              world.collisionSettings().penetration_slop);
  }
}

INSTANTIATE_TEST_SUITE_P(AllIntegrators, RestsAtOneSubstep, everyIntegrator(), integratorParamName);

TEST(ContactDeterminism, SameCallsGiveBitIdenticalStatesAndCopiesContinueAlike) {
  const auto build = [] {
    World world = groundWorld(Material{0.3, 0.2});
    CollisionSettings settings;
    settings.particle_collisions = true;
    settings.broadphase = Broadphase::kUniformGrid;
    settings.continuous = true;
    EXPECT_TRUE(world.setCollisionSettings(settings).isOk());
    for (int i = 0; i < 50; ++i) {
      addBall(world, Vec3(0.05 * (i % 7), 0.03 * (i % 5), 0.3 + 0.25 * i));
    }
    const ParticleId a = world.particles().idAt(0);
    const ParticleId b = world.particles().idAt(1);
    EXPECT_TRUE(world.addLink(Cable::between(a, b, 0.5, 0.2)).isOk());
    return world;
  };
  World first = build();
  World second = build();
  for (int s = 0; s < 120; ++s) {
    first.step();
    second.step();
  }
  EXPECT_EQ(first.stateHash(), second.stateHash());
  World copy = first;
  for (int s = 0; s < 60; ++s) {
    first.step();
    copy.step();
  }
  EXPECT_EQ(first.stateHash(), copy.stateHash());
}

TEST(ContactSettings, ValidationAndMaterials) {
  World world;
  CollisionSettings bad;
  bad.particle_restitution = 1.5;
  EXPECT_FALSE(world.setCollisionSettings(bad).isOk());
  bad = CollisionSettings{};
  bad.max_iterations = 0;
  EXPECT_FALSE(world.setCollisionSettings(bad).isOk());
  bad = CollisionSettings{};
  bad.penetration_slop = std::nan("");
  EXPECT_FALSE(world.setCollisionSettings(bad).isOk());
  EXPECT_EQ(world.collisionSettings().max_iterations, CollisionSettings{}.max_iterations);

  // Two particles with their own materials: restitution is the mean (0.2 and 0.8 give 0.5).
  CollisionSettings settings;
  settings.particle_collisions = true;
  settings.particle_restitution = 0.0;
  ASSERT_TRUE(world.setCollisionSettings(settings).isOk());
  ParticleSpec spec;
  spec.radius = 0.5;
  spec.velocity = Vec3(1, 0, 0);
  const ParticleId a = *world.addParticle(spec);
  spec.position = Vec3(0.99, 0, 0);
  spec.velocity = Vec3(-1, 0, 0);
  const ParticleId b = *world.addParticle(spec);
  EXPECT_FALSE(world.setParticleMaterial(a, Material{2.0, 0.0}).isOk());
  ASSERT_TRUE(world.setParticleMaterial(a, Material{0.2, 0.0}).isOk());
  ASSERT_TRUE(world.setParticleMaterial(b, Material{0.8, 0.0}).isOk());
  world.step();
  EXPECT_NEAR(world.particles().velocities()(0, 0), -0.5, 1e-12);
  EXPECT_NEAR(world.particles().velocities()(0, 1), 0.5, 1e-12);

  // clear() removes colliders and links, keeps the settings.
  ASSERT_TRUE(world.addCollider(PlaneCollider{}).isOk());
  ASSERT_TRUE(world.addLink(Rod::between(a, b, 1.0)).isOk());
  world.clear();
  EXPECT_TRUE(world.colliders().empty());
  EXPECT_TRUE(world.links().empty());
  EXPECT_TRUE(world.collisionSettings().particle_collisions);
}

TEST(ContactStatsReport, ResidualsAreSmallOnASettledScene) {
  World world = groundWorld(Material{0.0, 0.5});
  for (int i = 0; i < 5; ++i) addBall(world, Vec3(0.3 * i, 0, 0.1));
  for (int s = 0; s < 60; ++s) world.step();
  const ContactStats& stats = world.lastContactStats();
  EXPECT_EQ(stats.contacts, 5u);
  EXPECT_GE(stats.iterations, 2);
  EXPECT_LE(stats.max_penetration, world.collisionSettings().penetration_slop);
  EXPECT_LT(stats.max_closing_velocity, 1e-9);
  EXPECT_EQ(stats.dropped, 0u);
}

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
