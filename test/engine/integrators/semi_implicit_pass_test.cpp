// The semi-implicit Euler pass (and the force stage the other integrators ask) skips reading own
// accelerations when no particle has one, and the pass skips storing the substep's accelerations
// when no contact phase reads them: both must leave every bit of the state as reading and storing
// them does.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "integrator_params.h"
#include "mass_aggregate_sim/engine/world/world.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

constexpr Real kDt = 1.0 / 60.0;

World freeWorld(const Vec3& gravity, const Integrator integrator = Integrator::kSemiImplicitEuler) {
  WorldConfig config;
  config.dt = kDt;
  config.integrator = integrator;
  config.gravity = gravity;
  return World(config);
}

ParticleSpec movingSpec(const Vec3& velocity, const Vec3& own_acceleration) {
  ParticleSpec spec;
  spec.position = Vec3(1.0, 2.0, 3.0);
  spec.velocity = velocity;
  spec.acceleration = own_acceleration;
  spec.damping = 0.9;
  return spec;
}

bool sameBits(const Vec3& a, const Vec3& b) { return std::memcmp(a.data(), b.data(), 3 * 8) == 0; }

Vec3 velocityOf(const World& world, const ParticleId id) {
  return world.particles().velocities().col(*world.particles().find(id));
}
Vec3 positionOf(const World& world, const ParticleId id) {
  return world.particles().positions().col(*world.particles().find(id));
}

// g + a_own with a_own = -0 keeps g = -0's sign, g + (+0) does not: a particle whose own
// acceleration is -0 must be read, not taken for one without.
TEST(SemiImplicitPass, ANegativeZeroOwnAccelerationIsRead) {
  const Vec3 gravity(-0.0, -9.81, 0.0);
  const Vec3 still_x(-0.0, 1.0, 0.0);
  World world = freeWorld(gravity);
  const ParticleId negative = world.addParticle(movingSpec(still_x, Vec3(-0.0, 0.0, 0.0))).value();
  world.step();
  EXPECT_TRUE(std::signbit(velocityOf(world, negative).x()));  // -0 + (-0) h = -0

  World plain = freeWorld(gravity);
  const ParticleId none = plain.addParticle(movingSpec(still_x, Vec3::Zero())).value();
  plain.step();
  EXPECT_FALSE(std::signbit(velocityOf(plain, none).x()));  // -0 + (-0 + 0) h = +0
}

// The same particle stepped with its own acceleration skipped (no particle has one) and read
// (another particle has one) ends in the same bits, signed zeros of gravity included: the
// semi-implicit Euler pass and, for the other integrators, the force stage.
class ZeroOwnAccelerations : public ::testing::TestWithParam<Integrator> {};

TEST_P(ZeroOwnAccelerations, AreSkippedWithoutChangingABit) {
  for (const Vec3& gravity : {Vec3(-0.0, -9.81, 0.0), Vec3(0.3, -9.81, -0.0)}) {
    const ParticleSpec spec = movingSpec(Vec3(-0.0, 2.0, 0.5), Vec3::Zero());
    World alone = freeWorld(gravity, GetParam());
    const ParticleId skipped = alone.addParticle(spec).value();
    World beside = freeWorld(gravity, GetParam());
    const ParticleId read = beside.addParticle(spec).value();
    beside.addParticle(movingSpec(Vec3::Zero(), Vec3(0.0, 4.0, 0.0))).value();
    for (int step = 0; step < 30; ++step) {
      alone.step();
      beside.step();
    }
    EXPECT_TRUE(sameBits(velocityOf(alone, skipped), velocityOf(beside, read))) << gravity;
    EXPECT_TRUE(sameBits(positionOf(alone, skipped), positionOf(beside, read))) << gravity;
  }
}

INSTANTIATE_TEST_SUITE_P(EveryIntegrator, ZeroOwnAccelerations, everyIntegrator(),
                         integratorParamName);

// Removing a particle moves the last one into its place: its own acceleration must still act.
TEST(SemiImplicitPass, AnOwnAccelerationActsAfterAnotherParticleIsRemoved) {
  World world = freeWorld(Vec3(0.0, -9.81, 0.0));
  const ParticleId first = world.addParticle(movingSpec(Vec3::Zero(), Vec3::Zero())).value();
  const ParticleId lifted =
      world.addParticle(movingSpec(Vec3::Zero(), Vec3(0.0, 9.81, 0.0))).value();
  ASSERT_TRUE(world.removeParticle(first).isOk());
  for (int step = 0; step < 10; ++step) world.step();
  EXPECT_EQ(velocityOf(world, lifted), Vec3(0.0, 0.0, 0.0));  // g + a_own = 0
  EXPECT_EQ(positionOf(world, lifted), Vec3(1.0, 2.0, 3.0));

  ASSERT_TRUE(world.removeParticle(lifted).isOk());
  const ParticleId falling = world.addParticle(movingSpec(Vec3::Zero(), Vec3::Zero())).value();
  world.step();
  EXPECT_LT(velocityOf(world, falling).y(), 0.0);
}

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
