#include "mass_aggregate_sim/node/simulation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace mass_aggregate_sim {
namespace node {
namespace {

using engine::ParticleId;
using engine::ParticleSpec;
using engine::Vec3;

engine::World makeScene(const Vec3& gravity = Vec3::Zero()) {
  engine::WorldConfig config;
  config.dt = 0.01;
  config.gravity = gravity;
  engine::World world(config);
  ParticleSpec spec;
  spec.name = "ball";
  spec.inverse_mass = 0.5;
  spec.position = Vec3(0, 0, 1);
  world.addParticle(spec);
  spec.name = "post";
  spec.inverse_mass = 0.0;
  spec.position = Vec3(1, 0, 1);
  world.addParticle(spec);
  return world;
}

ParticleSpec named(const std::string& name, const double mass = 1.0) {
  ParticleSpec spec;
  spec.name = name;
  spec.inverse_mass = 1.0 / mass;
  return spec;
}

ParticleRef byName(const std::string& name) { return ParticleRef{0, name}; }

Vec3 velocityOf(const Simulation& sim, const std::string& name) {
  const auto id = sim.world().particles().findByName(name);
  return sim.world().particles().velocities().col(*sim.world().particles().find(*id));
}

TEST(SimulationTest, SpawnReturnsIdsThatNameTheNewParticles) {
  Simulation sim(makeScene(), SimulationLimits{});
  const auto ids = sim.spawn({named("a"), named("b", 4.0)});
  ASSERT_TRUE(ids.isOk()) << ids.message();
  ASSERT_EQ(ids.value().size(), 2u);
  EXPECT_EQ(sim.world().particles().size(), 4u);
  EXPECT_EQ(sim.world().particles().findByName("b"), ids.value()[1]);
  const auto resolved = sim.resolve(ParticleRef{ids.value()[0].packed(), ""});
  ASSERT_TRUE(resolved.isOk());
  EXPECT_EQ(*resolved, ids.value()[0]);
}

TEST(SimulationTest, SpawnIsAllOrNothing) {
  Simulation sim(makeScene(), SimulationLimits{});
  const auto hash = sim.world().stateHash();
  ParticleSpec bad = named("bad");
  bad.position.y() = std::numeric_limits<double>::quiet_NaN();
  const auto refused = sim.spawn({named("fine"), bad});
  ASSERT_FALSE(refused.isOk());
  EXPECT_NE(refused.message().find("particles[1]: position is not finite"), std::string::npos)
      << refused.message();
  EXPECT_EQ(sim.world().particles().size(), 2u);
  EXPECT_EQ(sim.world().stateHash(), hash);

  const auto taken = sim.spawn({named("new"), named("ball")});
  ASSERT_FALSE(taken.isOk());
  EXPECT_NE(taken.message().find("'ball' is already taken"), std::string::npos);
  const auto twice = sim.spawn({named("x"), named("x")});
  ASSERT_FALSE(twice.isOk());
  EXPECT_EQ(sim.world().particles().size(), 2u);
  EXPECT_FALSE(sim.spawn({}).isOk());
}

TEST(SimulationTest, SpawnOverTheLimitIsRefused) {
  SimulationLimits limits;
  limits.max_particles = 4;
  Simulation sim(makeScene(), limits);
  EXPECT_TRUE(sim.spawn({named("a"), named("b")}).isOk());
  const auto refused = sim.spawn({named("c")});
  ASSERT_FALSE(refused.isOk());
  EXPECT_NE(refused.message().find("~max_particles (4)"), std::string::npos) << refused.message();
  EXPECT_EQ(sim.world().particles().size(), 4u);
}

TEST(SimulationTest, RemoveByIdAndNameIsAllOrNothing) {
  Simulation sim(makeScene(), SimulationLimits{});
  const auto ids = sim.spawn({named("a"), named("b")});
  ASSERT_TRUE(ids.isOk());
  const auto hash = sim.world().stateHash();
  const auto unknown = sim.remove({byName("a"), byName("nobody")});
  ASSERT_FALSE(unknown.isOk());
  EXPECT_NE(unknown.message().find("no particle named 'nobody'"), std::string::npos);
  EXPECT_EQ(sim.world().stateHash(), hash);
  const auto stale = sim.remove({ParticleRef{ParticleId{77, 3}.packed(), ""}});
  ASSERT_FALSE(stale.isOk());
  EXPECT_NE(stale.message().find("no particle with id"), std::string::npos);

  const auto removed = sim.remove({ParticleRef{ids.value()[0].packed(), ""}, byName("b")});
  ASSERT_TRUE(removed.isOk()) << removed.message();
  EXPECT_EQ(sim.world().particles().size(), 2u);
  // The removed id is stale now.
  EXPECT_FALSE(sim.resolve(ParticleRef{ids.value()[0].packed(), ""}).isOk());
}

TEST(SimulationTest, ImpulseChangesVelocityByJOverM) {
  Simulation sim(makeScene(), SimulationLimits{});
  const Vec3 impulse(3.0, -1.5, 0.25);
  const auto velocity = sim.applyImpulse(byName("ball"), impulse);
  ASSERT_TRUE(velocity.isOk()) << velocity.message();
  EXPECT_EQ(*velocity, impulse * 0.5);  // m = 2 kg
  EXPECT_EQ(velocityOf(sim, "ball"), impulse * 0.5);
  const auto hash = sim.world().stateHash();
  EXPECT_FALSE(sim.applyImpulse(byName("post"), impulse).isOk());  // immovable
  EXPECT_FALSE(sim.applyImpulse(byName("ball"), Vec3(0, INFINITY, 0)).isOk());
  EXPECT_EQ(sim.world().stateHash(), hash);
}

TEST(SimulationTest, ForceForADurationGivesFTimesTheSteps) {
  Simulation sim(makeScene(), SimulationLimits{});
  const Vec3 force(4.0, 0.0, -2.0);
  const auto steps =
      sim.applyForce(ForceRequest{byName("ball"), force, ForceMode::kDuration, 0.05});
  ASSERT_TRUE(steps.isOk()) << steps.message();
  EXPECT_EQ(*steps, 5u);  // 0.05 s at dt = 0.01 s
  for (int i = 0; i < 8; ++i) sim.step();
  // p = F t: m v = 2 kg * v
  EXPECT_TRUE((2.0 * velocityOf(sim, "ball")).isApprox(force * 0.05, 1e-12))
      << velocityOf(sim, "ball").transpose();
  EXPECT_EQ(sim.sustainedForceCount(), 0u);
}

TEST(SimulationTest, ForceUntilClearedActsUntilCleared) {
  Simulation sim(makeScene(), SimulationLimits{});
  const Vec3 force(1.0, 0.0, 0.0);
  ASSERT_TRUE(sim.applyForce(ForceRequest{byName("ball"), force, ForceMode::kUntilCleared, 0.0}));
  for (int i = 0; i < 10; ++i) sim.step();
  ASSERT_TRUE(sim.applyForce(ForceRequest{byName("ball"), Vec3::Zero(), ForceMode::kClear, 0.0}));
  for (int i = 0; i < 10; ++i) sim.step();
  EXPECT_TRUE((2.0 * velocityOf(sim, "ball")).isApprox(force * 0.1, 1e-12));
  EXPECT_FALSE(sim.applyForce(ForceRequest{byName("ball"), force, ForceMode::kClear, 0.0}));
}

TEST(SimulationTest, OneStepForceActsOnce) {
  Simulation sim(makeScene(), SimulationLimits{});
  ASSERT_TRUE(sim.applyForce(ForceRequest{byName("ball"), Vec3(2, 0, 0), ForceMode::kOneStep, 0}));
  for (int i = 0; i < 3; ++i) sim.step();
  EXPECT_TRUE((2.0 * velocityOf(sim, "ball")).isApprox(Vec3(2, 0, 0) * 0.01, 1e-12));
}

TEST(SimulationTest, BadForcesChangeNothing) {
  Simulation sim(makeScene(), SimulationLimits{});
  const auto hash = sim.world().stateHash();
  EXPECT_FALSE(
      sim.applyForce(ForceRequest{byName("ball"), Vec3(NAN, 0, 0), ForceMode::kUntilCleared, 0}));
  EXPECT_FALSE(
      sim.applyForce(ForceRequest{byName("ball"), Vec3(1, 0, 0), ForceMode::kDuration, -1.0}));
  EXPECT_FALSE(
      sim.applyForce(ForceRequest{byName("ball"), Vec3(1, 0, 0), ForceMode::kDuration, NAN}));
  EXPECT_FALSE(
      sim.applyForce(ForceRequest{byName("ghost"), Vec3(1, 0, 0), ForceMode::kOneStep, 0}));
  EXPECT_EQ(sim.sustainedForceCount(), 0u);
  sim.step();
  Simulation untouched(makeScene(), SimulationLimits{});
  untouched.step();
  EXPECT_EQ(sim.world().stateHash(), untouched.world().stateHash());
  EXPECT_NE(sim.world().stateHash(), hash);
}

TEST(SimulationTest, SetStateTeleportsAndRefusesBadValues) {
  Simulation sim(makeScene(), SimulationLimits{});
  ASSERT_TRUE(sim.setState(byName("ball"), Vec3(5, 6, 7), Vec3(1, 0, 0)));
  const auto i = *sim.world().particles().find(*sim.world().particles().findByName("ball"));
  EXPECT_EQ(Vec3(sim.world().particles().positions().col(i)), Vec3(5, 6, 7));
  EXPECT_EQ(velocityOf(sim, "ball"), Vec3(1, 0, 0));
  const auto hash = sim.world().stateHash();
  EXPECT_FALSE(sim.setState(byName("ball"), Vec3(0, 0, 0), Vec3(NAN, 0, 0)));
  EXPECT_FALSE(sim.setState(byName("post"), std::nullopt, Vec3(1, 0, 0)));
  EXPECT_FALSE(sim.setState(byName("ball"), std::nullopt, std::nullopt));
  EXPECT_EQ(sim.world().stateHash(), hash);
}

TEST(SimulationTest, LinksAreAddedAndRemovedById) {
  Simulation sim(makeScene(), SimulationLimits{});
  LinkRequest spring;
  spring.type = LinkType::kSpring;
  spring.a = byName("ball");
  spring.b = byName("post");
  spring.stiffness = 10.0;
  const auto id = sim.addLink(spring);
  ASSERT_TRUE(id.isOk()) << id.message();
  ASSERT_EQ(sim.world().generators().of<engine::Spring>().size(), 1u);
  EXPECT_DOUBLE_EQ(sim.world().generators().of<engine::Spring>()[0].rest_length,
                   1.0);  // current distance

  LinkRequest anchored;
  anchored.type = LinkType::kBungee;
  anchored.a = byName("ball");
  anchored.anchor = Vec3(0, 0, 3);
  anchored.stiffness = 5.0;
  anchored.rest_length = 0.5;
  ASSERT_TRUE(sim.addLink(anchored).isOk());
  const engine::Spring& bungee = sim.world().generators().of<engine::Spring>()[1];
  EXPECT_TRUE(bungee.anchored() && bungee.pull_only);
  EXPECT_DOUBLE_EQ(bungee.rest_length, 0.5);

  LinkRequest bad = spring;
  bad.stiffness = -1.0;
  EXPECT_FALSE(sim.addLink(bad).isOk());
  bad = spring;
  bad.b = byName("nobody");
  const auto unknown = sim.addLink(bad);
  ASSERT_FALSE(unknown.isOk());
  EXPECT_NE(unknown.message().find("b: no particle named 'nobody'"), std::string::npos);
  EXPECT_EQ(sim.world().generators().size(), 2u);

  EXPECT_TRUE(sim.removeLink(*id));
  EXPECT_FALSE(sim.removeLink(*id));
  EXPECT_EQ(sim.world().generators().size(), 1u);
}

TEST(SimulationTest, StepManyAndResetGiveExactTimesAndTheSceneBack) {
  Simulation sim(makeScene(Vec3(0, 0, -9.81)), SimulationLimits{});
  const auto scene_hash = sim.world().stateHash();
  ASSERT_TRUE(sim.stepMany(25));
  EXPECT_EQ(sim.world().stepCount(), 25u);
  EXPECT_DOUBLE_EQ(sim.world().time(), 0.25);
  EXPECT_FALSE(sim.stepMany(0));
  EXPECT_FALSE(sim.stepMany(sim.limits().max_steps_per_request + 1));
  EXPECT_EQ(sim.world().stepCount(), 25u);

  ASSERT_TRUE(sim.spawn({named("extra")}));
  ASSERT_TRUE(
      sim.applyForce(ForceRequest{byName("ball"), Vec3(1, 0, 0), ForceMode::kUntilCleared, 0.0}));
  sim.reset();
  EXPECT_EQ(sim.world().stateHash(), scene_hash);
  EXPECT_EQ(sim.world().particles().size(), 2u);
  EXPECT_EQ(sim.sustainedForceCount(), 0u);
  EXPECT_EQ(sim.world().time(), 0.0);
}

TEST(SimulationTest, SameRequestsInTheSameOrderGiveTheSameHash) {
  const auto run = [] {
    Simulation sim(makeScene(Vec3(0, 0, -9.81)), SimulationLimits{});
    sim.stepMany(3);
    sim.spawn({named("a"), named("b", 3.0)});
    sim.applyImpulse(byName("a"), Vec3(1, 2, 3));
    sim.applyForce(ForceRequest{byName("b"), Vec3(0, 1, 0), ForceMode::kDuration, 0.1});
    sim.stepMany(20);
    sim.remove({byName("a")});
    sim.stepMany(5);
    return sim.world().stateHash();
  };
  EXPECT_EQ(run(), run());
}

TEST(SimulationTest, CablesAndRodsAreLinksToo) {
  Simulation sim(makeScene(), SimulationLimits{});
  LinkRequest rod;
  rod.type = LinkType::kRod;
  rod.a = byName("ball");
  rod.b = byName("post");
  const auto rod_id = sim.addLink(rod);
  ASSERT_TRUE(rod_id.isOk()) << rod_id.message();
  ASSERT_EQ(sim.world().links().of<engine::Rod>().size(), 1u);
  EXPECT_DOUBLE_EQ(sim.world().links().of<engine::Rod>()[0].length, 1.0);
  LinkRequest cable;
  cable.type = LinkType::kCable;
  cable.a = byName("ball");
  cable.anchor = Vec3(0, 0, 3);
  cable.max_length = 2.5;
  cable.restitution = 0.2;
  const auto cable_id = sim.addLink(cable);
  ASSERT_TRUE(cable_id.isOk()) << cable_id.message();
  ASSERT_EQ(sim.world().links().of<engine::Cable>().size(), 1u);
  EXPECT_TRUE(sim.world().links().of<engine::Cable>()[0].anchored());
  EXPECT_DOUBLE_EQ(sim.world().links().of<engine::Cable>()[0].max_length, 2.5);
  cable.restitution = 3.0;
  EXPECT_FALSE(sim.addLink(cable).isOk());
  EXPECT_TRUE(sim.removeLink(*rod_id));
  EXPECT_TRUE(sim.removeLink(*cable_id));
  EXPECT_TRUE(sim.world().links().empty());
}

// Reset copies the loaded world back: colliders, links and contact settings included, so the
// same steps after a reset give the same state as after the start.
TEST(SimulationTest, ResetRestoresContactsAndRepeatsBitForBit) {
  engine::WorldConfig config;
  config.dt = 0.01;
  config.gravity = Vec3(0, 0, -9.81);
  engine::World scene(config);
  engine::CollisionSettings settings;
  settings.particle_collisions = true;
  ASSERT_TRUE(scene.setCollisionSettings(settings));
  ASSERT_TRUE(scene.addCollider(engine::PlaneCollider{}).isOk());
  std::vector<ParticleId> ids;
  for (int i = 0; i < 27; ++i) {
    ParticleSpec spec;
    spec.position = Vec3(0.21 * (i % 3), 0.21 * ((i / 3) % 3), 0.3 + 0.21 * (i / 9));
    ids.push_back(*scene.addParticle(spec));
  }
  ASSERT_TRUE(scene.addLink(engine::Cable::anchoredAt(ids[26], Vec3(0, 0, 2), 1.5, 0.0)).isOk());
  Simulation sim(scene, SimulationLimits{});
  ASSERT_TRUE(sim.stepMany(60));
  const auto first = sim.world().stateHash();
  EXPECT_GT(sim.world().lastContactStats().contacts, 0u);
  sim.reset();
  EXPECT_EQ(sim.world().colliders().size(), 1u);
  EXPECT_EQ(sim.world().links().size(), 1u);
  EXPECT_TRUE(sim.world().collisionSettings().particle_collisions);
  ASSERT_TRUE(sim.stepMany(60));
  EXPECT_EQ(sim.world().stateHash(), first);
  Simulation fresh(scene, SimulationLimits{});
  ASSERT_TRUE(fresh.stepMany(60));
  EXPECT_EQ(fresh.world().stateHash(), first);
}

}  // namespace
}  // namespace node
}  // namespace mass_aggregate_sim
