#include "mass_aggregate_sim/node/settings.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "mass_aggregate_sim/engine/integrators/integrator.h"
#include "mass_aggregate_sim/node/input_limits.h"
#include "mass_aggregate_sim/node/links.h"
#include "mass_aggregate_sim/node/reconfigure.h"
#include "mass_aggregate_sim/node/simulation.h"

namespace mass_aggregate_sim {
namespace node {
namespace {

using engine::Vec3;

PhysicsSettings base() {
  PhysicsSettings s;
  s.config.dt = 1.0 / 60.0;
  s.config.gravity = Vec3(0, 0, -9.81);
  return s;
}

engine::World scene() {
  engine::WorldConfig config;
  config.dt = 0.01;
  config.gravity = Vec3(0, 0, -9.81);
  engine::World world(config);
  engine::ParticleSpec spec;
  spec.name = "ball";
  spec.inverse_mass = 0.5;
  spec.position = Vec3(0, 0, 1);
  world.addParticle(spec);
  return world;
}

TEST(LiveSettingsTest, AppliesGoodValues) {
  LiveSettings wanted = liveSettingsOf(base(), 30.0, false);
  wanted.rate = 200.0;
  wanted.integrator = "rk4";
  wanted.gravity = Vec3(0, 0, -3);
  wanted.particle_collisions = true;
  wanted.max_iterations = 7;
  wanted.body_substeps = 8;
  wanted.body_iterations = 3;
  wanted.body_relax_iterations = 1;
  wanted.body_sleep = false;
  const auto applied = applyLiveSettings(wanted, base());
  ASSERT_TRUE(applied) << applied.message();
  EXPECT_EQ(applied.value().config.dt, 1.0 / 200.0);
  EXPECT_EQ(applied.value().config.integrator, engine::Integrator::kRk4);
  EXPECT_EQ(applied.value().config.gravity, Vec3(0, 0, -3));
  EXPECT_TRUE(applied.value().collisions.particle_collisions);
  EXPECT_EQ(applied.value().collisions.max_iterations, 7);
  EXPECT_EQ(applied.value().bodies.substeps, 8);
  EXPECT_EQ(applied.value().bodies.iterations, 3);
  EXPECT_EQ(applied.value().bodies.relax_iterations, 1);
  EXPECT_FALSE(applied.value().bodies.sleep);
  // The body settings that are not live stay as they were.
  EXPECT_EQ(applied.value().bodies.contact_hertz, base().bodies.contact_hertz);
  // And back: what the reconfigure server shows is what was applied.
  EXPECT_TRUE(sameSettings(liveSettingsOf(*applied, 30.0, false), wanted));
  EXPECT_TRUE(sameSettings(fromSimConfig(toSimConfig(wanted)), wanted));
}

TEST(LiveSettingsTest, RefusesBadValuesNamingTheParameter) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<std::pair<std::function<void(LiveSettings&)>, std::string>> cases = {
      {[](LiveSettings& s) { s.rate = 0.0; }, "rate: must be in (0, 100000] Hz"},
      {[nan](LiveSettings& s) { s.rate = nan; }, "rate:"},
      {[](LiveSettings& s) { s.substeps = 0; }, "substeps: must be in [1, 1000]"},
      {[](LiveSettings& s) { s.integrator = "leapfrog"; }, "integrator: unknown integrator"},
      {[nan](LiveSettings& s) { s.gravity.x() = nan; }, "gravity"},
      {[](LiveSettings& s) { s.gravity.z() = -1e7; }, "gravity"},
      {[](LiveSettings& s) { s.divergence_policy = "explode"; }, "divergence_policy: unknown"},
      {[](LiveSettings& s) { s.particle_restitution = 1.5; },
       "particle_restitution: must be in [0, 1], got 1.5"},
      {[nan](LiveSettings& s) { s.particle_friction = nan; }, "particle_friction"},
      {[](LiveSettings& s) { s.penetration_slop = -1.0; },
       "penetration_slop: must be in [0, 1] m, got -1"},
      {[](LiveSettings& s) { s.max_iterations = 0; }, "max_iterations"},
      {[](LiveSettings& s) { s.publish_rate = 0.0; }, "publish_rate"},
      {[](LiveSettings& s) { s.body_substeps = 0; }, "body_substeps: must be in [1, 64], got 0"},
      {[](LiveSettings& s) { s.body_iterations = 65; }, "body_iterations: must be in [1, 64]"},
      {[](LiveSettings& s) { s.body_relax_iterations = -1; },
       "body_relax_iterations: must be in [0, 64], got -1"},
  };
  for (const auto& [change, expected] : cases) {
    LiveSettings wanted = liveSettingsOf(base(), 30.0, false);
    change(wanted);
    const auto applied = applyLiveSettings(wanted, base());
    ASSERT_FALSE(applied) << expected;
    EXPECT_NE(applied.message().find(expected), std::string::npos) << applied.message();
  }
}

TEST(LiveSettingsTest, ARefusalQuotesAtMostAHundredCharacters) {
  LiveSettings wanted = liveSettingsOf(base(), 30.0, false);
  wanted.integrator = std::string(100000, 'x');
  const auto applied = applyLiveSettings(wanted, base());
  ASSERT_FALSE(applied);
  EXPECT_LT(applied.message().size(), 400u) << applied.message().substr(0, 400);
  EXPECT_NE(applied.message().find("(100000 characters)"), std::string::npos);
}

TEST(QuoteInputTest, CutsLongTextAndSaysHowLong) {
  EXPECT_EQ(quoteInput("ball"), "'ball'");
  EXPECT_EQ(quoteInput(std::string(100, 'a')), "'" + std::string(100, 'a') + "'");
  EXPECT_EQ(quoteInput(std::string(101, 'a')),
            "'" + std::string(100, 'a') + "'... (101 characters)");
  engine::World world = scene();
  const auto missing = resolveParticle(world, ParticleRef{0, std::string(100000, 'n')});
  ASSERT_FALSE(missing);
  EXPECT_LT(missing.message().size(), 200u);
}

TEST(ConfigurationTest, NamesEverySettingExactly) {
  PhysicsSettings s = base();
  s.config.gravity = Vec3(0, 0.1, -9.81);
  const std::string text = describeConfiguration(s);
  EXPECT_NE(text.find("integrator: semi_implicit_euler\n"), std::string::npos) << text;
  EXPECT_NE(text.find("rate: 60\n"), std::string::npos) << text;
  EXPECT_NE(text.find("dt: 0.016666666666666666\n"), std::string::npos) << text;
  EXPECT_NE(text.find("gravity: [0, 0.10000000000000001, -9.8100000000000005]\n"),
            std::string::npos)
      << text;
  for (const char* key : {"substeps", "auto_substep", "divergence_policy", "particle_collisions",
                          "broadphase", "continuous", "particle_restitution", "particle_friction",
                          "max_iterations", "penetration_slop", "collide_linked"}) {
    EXPECT_NE(text.find(std::string(key) + ": "), std::string::npos) << key;
  }
}

TEST(SceneHashTest, CoversTheConfigurationAndWhatTheStateHashLeavesOut) {
  const engine::World world = scene();
  const std::uint64_t hash = sceneHash(world);
  EXPECT_EQ(sceneHash(scene()), hash);
  engine::World other = scene();
  engine::WorldConfig config = other.config();
  config.integrator = engine::Integrator::kRk4;
  ASSERT_TRUE(other.setConfig(config));
  EXPECT_EQ(other.stateHash(), world.stateHash());
  EXPECT_NE(sceneHash(other), hash);
  engine::World heavier = scene();
  engine::ParticleSpec spec;
  spec.inverse_mass = 0.25;
  spec.position = Vec3(0, 0, 1);
  engine::World lighter = scene();
  spec.inverse_mass = 0.5;
  ASSERT_TRUE(heavier.addParticle(spec));
  spec.inverse_mass = 0.125;
  ASSERT_TRUE(lighter.addParticle(spec));
  EXPECT_NE(sceneHash(heavier), sceneHash(lighter));
  engine::World rough = scene();
  engine::CollisionSettings collisions = rough.collisionSettings();
  collisions.particle_friction = 0.3;
  ASSERT_TRUE(rough.setCollisionSettings(collisions));
  EXPECT_NE(sceneHash(rough), hash);
}

TEST(SimulationConfigureTest, SettingsLastAcrossReset) {
  Simulation sim(scene(), SimulationLimits{});
  PhysicsSettings settings = sim.settings();
  settings.config.gravity = Vec3(0, 0, -2);
  settings.config.integrator = engine::Integrator::kVelocityVerlet;
  ASSERT_TRUE(sim.configure(settings));
  sim.step();
  sim.reset();
  EXPECT_EQ(sim.world().config().gravity, Vec3(0, 0, -2));
  EXPECT_EQ(sim.world().config().integrator, engine::Integrator::kVelocityVerlet);
  EXPECT_EQ(sim.world().stepCount(), 0u);
  settings.config.dt = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(sim.configure(settings));
  EXPECT_EQ(sim.world().config().dt, 0.01);
}

TEST(SimulationConfigureTest, BodySettingsApplyLiveAndWakeTheBodiesOnlyWhenTheyChange) {
  Simulation sim(scene(), SimulationLimits{});
  engine::BodySpec spec;
  spec.name = "crate";
  engine::BodyShapeSpec shape;
  shape.geometry = engine::BoxShape{Vec3::Constant(0.5)};
  spec.shapes = {shape};
  spec.pose.position = Vec3(5, 0, 0);
  spec.mass = 1.0;
  ASSERT_TRUE(sim.spawnBodies({spec}));
  PhysicsSettings settings = sim.settings();
  settings.config.gravity = Vec3::Zero();
  ASSERT_TRUE(sim.configure(settings));
  for (int i = 0; i < 60; ++i) sim.step();  // at rest without gravity: asleep after 0.5 s
  const auto awake = [&] { return sim.world().bodies().awake(0); };
  ASSERT_FALSE(awake());
  settings.collisions.max_iterations = 9;  // no body setting changes: it sleeps on
  ASSERT_TRUE(sim.configure(settings));
  EXPECT_FALSE(awake());
  settings.bodies.iterations = 3;
  ASSERT_TRUE(sim.configure(settings));
  EXPECT_EQ(sim.world().bodySettings().iterations, 3);
  EXPECT_TRUE(awake());
  settings.bodies.substeps = 0;
  EXPECT_FALSE(sim.configure(settings));
  EXPECT_EQ(sim.world().bodySettings().substeps, 4);
  sim.reset();
  EXPECT_EQ(sim.world().bodySettings().iterations, 3);
}

}  // namespace
}  // namespace node
}  // namespace mass_aggregate_sim
