// Applied forces and impulses under every integrator: a force F held for n steps gives exactly
// n F dt of momentum, an impulse J exactly J, a constant applied force moves a particle as an
// equal gravity does, and none of these (nor setting a state or adding a particle) changes how
// any other particle moves.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "integrator_params.h"
#include "mass_aggregate_sim/engine/world/world.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

constexpr Real kDt = 1.0 / 60.0;
constexpr Real kMass = 2.0;

World freeWorld(const Integrator integrator, const Vec3& gravity) {
  WorldConfig config;
  config.dt = kDt;
  config.integrator = integrator;
  config.gravity = gravity;
  return World(config);
}

ParticleId addBall(World& world, const Vec3& position, const Vec3& velocity) {
  ParticleSpec spec;
  spec.position = position;
  spec.velocity = velocity;
  spec.inverse_mass = 1.0 / kMass;
  return world.addParticle(spec).value();
}

Vec3 momentum(const World& world, const ParticleId id) {
  return kMass * world.particles().velocities().col(*world.particles().find(id));
}

Vec3 position(const World& world, const ParticleId id) {
  return world.particles().positions().col(*world.particles().find(id));
}

void expectNearRelative(const Vec3& actual, const Vec3& expected, const Real relative,
                        const char* what) {
  EXPECT_LE((actual - expected).norm(), relative * expected.norm())
      << what << ": " << actual.transpose() << " vs " << expected.transpose();
}

class AppliedForce : public ::testing::TestWithParam<Integrator> {};

// A forced ball and its unforced twin, side by side in one world (they never meet): the
// difference of their momenta is what the force gave.
struct Twins {
  World world;
  ParticleId forced;
  ParticleId twin;
};

Twins makeTwins(const Integrator integrator) {
  Twins t{freeWorld(integrator, Vec3(0.0, 0.0, -9.81)), {}, {}};
  t.forced = addBall(t.world, Vec3(0.0, 0.0, 10.0), Vec3(1.0, 2.0, 3.0));
  t.twin = addBall(t.world, Vec3(100.0, 0.0, 10.0), Vec3(1.0, 2.0, 3.0));
  return t;
}

Vec3 given(const Twins& t) { return momentum(t.world, t.forced) - momentum(t.world, t.twin); }

TEST_P(AppliedForce, OneStepForceGivesExactlyFDt) {
  Twins t = makeTwins(GetParam());
  for (int i = 0; i < 5; ++i) t.world.step();  // a history to keep
  const Vec3 force(3.0, -4.0, 12.0);
  ASSERT_TRUE(t.world.addForce(t.forced, force));
  t.world.step();
  expectNearRelative(given(t), force * kDt, 1e-12, "right after the step");
  for (int i = 0; i < 10; ++i) t.world.step();
  expectNearRelative(given(t), force * kDt, 1e-12, "ten steps later");
}

TEST_P(AppliedForce, ForceForNStepsGivesExactlyNFDt) {
  Twins t = makeTwins(GetParam());
  for (int i = 0; i < 3; ++i) t.world.step();
  const Vec3 force(-6.0, 1.5, 2.0);
  constexpr int kSteps = 37;
  for (int i = 0; i < kSteps; ++i) {
    ASSERT_TRUE(t.world.addForce(t.forced, force));
    t.world.step();
  }
  expectNearRelative(given(t), kSteps * kDt * force, 1e-12, "when the force ends");
  for (int i = 0; i < 10; ++i) t.world.step();
  expectNearRelative(given(t), kSteps * kDt * force, 1e-12, "ten steps later");
}

TEST_P(AppliedForce, ImpulseGivesExactlyJ) {
  Twins t = makeTwins(GetParam());
  for (int i = 0; i < 7; ++i) t.world.step();
  const Vec3 impulse(0.5, -2.0, 1.0);
  ASSERT_TRUE(t.world.applyImpulse(t.forced, impulse));
  expectNearRelative(given(t), impulse, 1e-12, "at once");
  for (int i = 0; i < 10; ++i) t.world.step();
  expectNearRelative(given(t), impulse, 1e-12, "ten steps later");
}

TEST_P(AppliedForce, ConstantForceMovesABallAsAnEqualGravityDoes) {
  const Vec3 g(0.0, 0.0, -9.81);
  World pushed = freeWorld(GetParam(), Vec3::Zero());
  World falling = freeWorld(GetParam(), g);
  const ParticleId a = addBall(pushed, Vec3(0.0, 0.0, 5.0), Vec3(4.0, 0.0, 7.0));
  const ParticleId b = addBall(falling, Vec3(0.0, 0.0, 5.0), Vec3(4.0, 0.0, 7.0));
  for (int i = 0; i < 120; ++i) {
    ASSERT_TRUE(pushed.addForce(a, kMass * g));
    pushed.step();
    falling.step();
    expectNearRelative(position(pushed, a), position(falling, b), 1e-12, "position");
    expectNearRelative(momentum(pushed, a), momentum(falling, b), 1e-12, "momentum");
  }
}

// Two balls, each on its own spring (no dashpots), far apart: whatever is done to the first, the
// second moves bit for bit as it does alone.
TEST_P(AppliedForce, RequestsOnOneParticleLeaveTheOthersAlone) {
  const auto scene = [&](const bool with_neighbour) {
    World world = freeWorld(GetParam(), Vec3(0.0, 0.0, -9.81));
    const ParticleId watched = addBall(world, Vec3(0.0, 0.0, 1.0), Vec3(0.5, 0.0, 0.0));
    EXPECT_TRUE(world.addGenerator(Spring::anchoredAt(watched, Vec3(0.0, 0.0, 2.0), 40.0, 1.0)));
    if (with_neighbour) {
      const ParticleId other = addBall(world, Vec3(50.0, 0.0, 1.0), Vec3::Zero());
      EXPECT_TRUE(world.addGenerator(Spring::anchoredAt(other, Vec3(50.0, 0.0, 2.0), 90.0, 1.0)));
    }
    return std::make_pair(std::move(world), watched);
  };
  // Named pairs, not structured bindings: lambdas may not capture those before C++20.
  auto alone_scene = scene(false);
  auto busy_scene = scene(true);
  World& alone = alone_scene.first;
  World& busy = busy_scene.first;
  const ParticleId alone_id = alone_scene.second;
  const ParticleId busy_id = busy_scene.second;
  const ParticleId other = busy.particles().idAt(1);
  const auto expectSame = [&](const char* after) {
    EXPECT_EQ(position(busy, busy_id), position(alone, alone_id)) << after;
    EXPECT_EQ(momentum(busy, busy_id), momentum(alone, alone_id)) << after;
  };
  const auto stepBoth = [&](const int n) {
    for (int i = 0; i < n; ++i) {
      alone.step();
      busy.step();
    }
  };
  stepBoth(10);
  expectSame("steps");
  ASSERT_TRUE(busy.addForce(other, Vec3(1.0, 2.0, 3.0)));
  stepBoth(3);
  expectSame("a force on the other");
  ASSERT_TRUE(busy.applyImpulse(other, Vec3(0.0, 1.0, 0.0)));
  stepBoth(3);
  expectSame("an impulse on the other");
  ASSERT_TRUE(busy.setVelocity(other, Vec3(0.0, 0.0, 1.0)));
  ASSERT_TRUE(busy.setPosition(other, Vec3(50.0, 1.0, 1.0)));
  stepBoth(3);
  expectSame("setting the other's state");
  ParticleSpec spec;
  spec.position = Vec3(-50.0, 0.0, 0.0);
  ASSERT_TRUE(busy.addParticle(spec).isOk());
  stepBoth(3);
  expectSame("a new particle");
  ASSERT_TRUE(busy.removeParticle(other));
  stepBoth(3);
  expectSame("removing the other");
}

INSTANTIATE_TEST_SUITE_P(EveryIntegrator, AppliedForce, everyIntegrator(), integratorParamName);

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
