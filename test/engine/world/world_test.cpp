// World bookkeeping: immovable particles, time keeping, the accumulator, substeps, validation,
// determinism and divergence reports.
#include "mass_aggregate_sim/engine/world/world.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace mass_aggregate_sim {
namespace engine {
namespace {

ParticleSpec particleAt(const Vec3& position, const Real mass = 1.0) {
  ParticleSpec spec;
  spec.position = position;
  spec.inverse_mass = mass > 0.0 ? 1.0 / mass : 0.0;
  spec.damping = 0.95;
  return spec;
}

// A small scene that uses every force generator kind.
void buildScene(World& world) {
  std::vector<ParticleId> chain;
  for (int i = 0; i < 8; ++i) {
    chain.push_back(*world.addParticle(particleAt(Vec3(0.5 * i, 0.1 * i, 2.0), 1.0 + 0.1 * i)));
  }
  const ParticleId anchor = *world.addParticle(particleAt(Vec3(-0.5, 0.0, 2.0), 0.0));
  ASSERT_TRUE(world.addGenerator(Spring::between(anchor, chain[0], 50.0, 0.5, 0.2)));
  for (std::size_t i = 0; i + 1 < chain.size(); ++i) {
    if (i % 2 == 0) {
      ASSERT_TRUE(world.addGenerator(Spring::between(chain[i], chain[i + 1], 50.0, 0.5, 0.2)));
    } else {
      ASSERT_TRUE(world.addGenerator(
          Spring::between(chain[i], chain[i + 1], 40.0, 0.4, 0.1).pullingOnly()));
    }
  }
  ASSERT_TRUE(
      world.addGenerator(Spring::anchoredAt(chain[7], Vec3(4.0, 0.0, 3.0), 20.0, 1.0, 0.0)));
  ASSERT_TRUE(world.addGenerator(
      Spring::anchoredAt(chain[3], Vec3(1.5, 0.0, 4.0), 10.0, 1.5, 0.0).pullingOnly()));
  ASSERT_TRUE(world.addGenerator(Drag{chain[5], 0.1, 0.05}));
  ASSERT_TRUE(world.addGenerator(Buoyancy{chain[6], 0.2, 0.001, 1000.0, 1.8, Vec3::UnitZ()}));
  ASSERT_TRUE(world.addGenerator(StiffSpring{chain[2], Vec3(1.0, 0.2, 2.0), 500.0, 5.0}));
}

WorldConfig configFor(const Integrator integrator) {
  WorldConfig config;
  config.dt = 1.0 / 120.0;
  config.substeps = 2;
  config.integrator = integrator;
  config.gravity = Vec3(0.0, 0.0, -9.81);
  return config;
}

TEST(World, ImmovableParticlesNeverMove) {
  for (const Integrator integrator : allIntegrators()) {
    World world(configFor(integrator));
    buildScene(world);
    const ParticleId fixed = world.particles().idAt(world.particles().size() - 1);
    const std::size_t dense = *world.particles().find(fixed);
    ASSERT_EQ(world.particles().inverseMasses()[static_cast<Eigen::Index>(dense)], 0.0);
    const Vec3 start = world.particles().positions().col(static_cast<Eigen::Index>(dense));
    EXPECT_FALSE(world.applyImpulse(fixed, Vec3(1.0, 0.0, 0.0)).isOk());
    EXPECT_FALSE(world.setVelocity(fixed, Vec3(1.0, 0.0, 0.0)).isOk());
    EXPECT_TRUE(world.addForce(fixed, Vec3(100.0, 0.0, 0.0)).isOk());
    for (int i = 0; i < 500; ++i) world.step();
    const std::size_t now = *world.particles().find(fixed);
    EXPECT_EQ(world.particles().positions().col(static_cast<Eigen::Index>(now)), start)
        << integratorName(integrator);
    EXPECT_TRUE(world.particles().velocities().col(static_cast<Eigen::Index>(now)).isZero(0.0));
  }
}

TEST(World, SameSceneAndStepsGiveBitIdenticalStates) {
  for (const Integrator integrator : allIntegrators()) {
    World first(configFor(integrator));
    World second(configFor(integrator));
    buildScene(first);
    buildScene(second);
    for (int i = 0; i < 10000; ++i) {
      if (i == 5000) {
        // the same command in the same order
        for (World* w : {&first, &second}) {
          ASSERT_TRUE(w->applyImpulse(w->particles().idAt(3), Vec3(0.5, 0.0, 1.0)));
        }
      }
      first.step();
      second.step();
    }
    EXPECT_EQ(first.stateHash(), second.stateHash()) << integratorName(integrator);
    EXPECT_EQ(first.divergenceCount(), 0u) << integratorName(integrator);
    // and a different command history gives a different hash
    ASSERT_TRUE(second.applyImpulse(second.particles().idAt(3), Vec3(1e-9, 0.0, 0.0)));
    first.step();
    second.step();
    EXPECT_NE(first.stateHash(), second.stateHash()) << integratorName(integrator);
  }
}

TEST(World, ACopyMidRunStepsOnBitIdentically) {
  // What a copy must carry: position Verlet's history, velocity Verlet's cached accelerations,
  // the energy guard's reference and the forces it evaluated ahead (semi-implicit Euler, one
  // substep), a force pending for the next step; what it derives again (the springs' layout,
  // damping factors, the stability report) must come out the same bits.
  for (const Integrator integrator : allIntegrators()) {
    for (const int substeps : {1, 2}) {
      WorldConfig config = configFor(integrator);
      config.substeps = substeps;
      World original(config);
      buildScene(original);
      for (int i = 0; i < 300; ++i) original.step();
      ASSERT_TRUE(original.addForce(original.particles().idAt(4), Vec3(0.0, 3.0, 0.0)));
      World constructed(original);
      World assigned;
      assigned = original;
      for (int i = 0; i < 300; ++i) {
        original.step();
        constructed.step();
        assigned.step();
      }
      const std::string what =
          std::string(integratorName(integrator)) + ", " + std::to_string(substeps) + " substeps";
      EXPECT_EQ(constructed.stateHash(), original.stateHash()) << what;
      EXPECT_EQ(assigned.stateHash(), original.stateHash()) << what;
      EXPECT_EQ(original.divergenceCount(), 0u) << what;
    }
  }
}

TEST(World, AMovedFromWorldIsEmptyAndUsable) {
  World original(configFor(Integrator::kVelocityVerlet));
  buildScene(original);
  original.step();
  const std::uint64_t hash = original.stateHash();
  World moved(std::move(original));
  EXPECT_EQ(moved.stateHash(), hash);
  // NOLINTNEXTLINE(bugprone-use-after-move): what is left must still be a world.
  original.clear();
  original.step();
  EXPECT_EQ(original.particles().size(), 0u);
  ASSERT_TRUE(original.addParticle(particleAt(Vec3::Zero())));
  original.step();
  EXPECT_EQ(original.divergenceCount(), 0u);
}

TEST(World, TimeIsExactMultipleOfDtAndSurvivesDtChange) {
  WorldConfig config;
  config.dt = 0.1;
  World world(config);
  for (int i = 0; i < 1000; ++i) world.step();
  EXPECT_EQ(world.time(), 1000 * 0.1);
  EXPECT_EQ(world.stepCount(), 1000u);
  config.dt = 0.01;
  ASSERT_TRUE(world.setConfig(config));
  for (int i = 0; i < 7; ++i) world.step();
  EXPECT_EQ(world.time(), 1000 * 0.1 + 7 * 0.01);
}

TEST(World, AccumulatorTakesWholeStepsAndClampsLongFrames) {
  WorldConfig config;
  config.dt = 0.01;
  config.max_frame_time = 0.1;
  World world(config);
  EXPECT_EQ(world.advance(0.025), 2);
  EXPECT_NEAR(world.accumulatorAlpha(), 0.5, 1e-9);
  EXPECT_EQ(world.advance(0.005), 1);  // 0.005 left + 0.005 = one step
  EXPECT_EQ(world.advance(5.0), 10);   // a 5 s stall is clamped to 0.1 s
  EXPECT_EQ(world.advance(-1.0), 0);
  EXPECT_EQ(world.advance(std::numeric_limits<Real>::quiet_NaN()), 0);
  EXPECT_EQ(world.stepCount(), 13u);
}

TEST(World, SubstepsSplitTheStep) {
  // Explicit Euler with 4 substeps of dt/4 equals 4 steps of dt/4.
  WorldConfig coarse;
  coarse.dt = 0.04;
  coarse.substeps = 4;
  coarse.integrator = Integrator::kExplicitEuler;
  coarse.gravity = Vec3(0.0, 0.0, -9.81);
  WorldConfig fine = coarse;
  fine.dt = 0.01;
  fine.substeps = 1;
  World a(coarse);
  World b(fine);
  ParticleSpec spec;
  spec.velocity = Vec3(1.0, 2.0, 3.0);
  ASSERT_TRUE(a.addParticle(spec));
  ASSERT_TRUE(b.addParticle(spec));
  a.step();
  for (int i = 0; i < 4; ++i) b.step();
  EXPECT_TRUE(a.particles().positions().isApprox(b.particles().positions(), 1e-15));
  EXPECT_EQ(a.stepCount(), 1u);
}

TEST(World, DampingKeepsFractionPerSecond) {
  // v' = v d^dt with no force: after 1 s the speed is d times the start, whatever the step.
  for (const Real dt : {0.1, 0.01, 1.0 / 60.0}) {
    WorldConfig config;
    config.dt = dt;
    World world(config);
    ParticleSpec spec;
    spec.velocity = Vec3(2.0, 0.0, 0.0);
    spec.damping = 0.5;
    ASSERT_TRUE(world.addParticle(spec));
    while (world.time() < 1.0 - 1e-9) world.step();
    EXPECT_NEAR(world.particles().velocities()(0, 0), 1.0, 1e-12) << dt;
  }
}

TEST(World, ImpulseChangesVelocityByJOverM) {
  World world;
  const ParticleId p = *world.addParticle(particleAt(Vec3::Zero(), 4.0));
  ASSERT_TRUE(world.applyImpulse(p, Vec3(2.0, -8.0, 1.0)));
  EXPECT_EQ(world.particles().velocities().col(0), Vec3(0.5, -2.0, 0.25));
}

TEST(World, ExternalForceActsForOneStepOnly) {
  WorldConfig config;
  config.dt = 0.1;
  World world(config);
  ParticleSpec spec = particleAt(Vec3::Zero(), 2.0);
  spec.damping = 1.0;
  const ParticleId p = *world.addParticle(spec);
  ASSERT_TRUE(world.addForce(p, Vec3(4.0, 0.0, 0.0)));
  world.step();
  EXPECT_NEAR(world.particles().velocities()(0, 0), 0.2, 1e-15);  // F/m dt = 2 * 0.1
  world.step();
  EXPECT_NEAR(world.particles().velocities()(0, 0), 0.2, 1e-15);
}

TEST(World, RefusedRequestsChangeNothing) {
  World world(configFor(Integrator::kSemiImplicitEuler));
  buildScene(world);
  const std::uint64_t before = world.stateHash();
  const std::size_t generators = world.generators().size();
  const Real nan = std::numeric_limits<Real>::quiet_NaN();
  const Real inf = std::numeric_limits<Real>::infinity();
  const ParticleId a = world.particles().idAt(0);
  const ParticleId b = world.particles().idAt(1);
  const ParticleId stale{a.index, a.generation + 1};

  ParticleSpec bad = particleAt(Vec3(nan, 0.0, 0.0));
  EXPECT_FALSE(world.addParticle(bad));
  bad = particleAt(Vec3::Zero());
  bad.inverse_mass = -1.0;
  EXPECT_FALSE(world.addParticle(bad));
  EXPECT_FALSE(world.setPosition(a, Vec3(inf, 0.0, 0.0)));
  EXPECT_FALSE(world.setVelocity(stale, Vec3::Zero()));
  EXPECT_FALSE(world.applyImpulse(a, Vec3(0.0, nan, 0.0)));
  EXPECT_FALSE(world.addForce(stale, Vec3::Zero()));
  EXPECT_FALSE(world.addGenerator(Spring::between(a, a, 1.0, 1.0, 0.0)));
  EXPECT_FALSE(world.addGenerator(Spring::between(a, stale, 1.0, 1.0, 0.0)));
  EXPECT_FALSE(world.addGenerator(Spring::between(a, b, -1.0, 1.0, 0.0)));
  EXPECT_FALSE(world.addGenerator(Spring::between(a, b, 1.0, nan, 0.0).pullingOnly()));
  EXPECT_FALSE(world.addGenerator(Drag{a, -0.1, 0.0}));
  EXPECT_FALSE(world.addGenerator(Buoyancy{a, 0.0, 1.0, 1000.0, 0.0, Vec3::UnitZ()}));
  EXPECT_FALSE(world.addGenerator(Buoyancy{a, 0.1, 1.0, 1000.0, 0.0, Vec3::Zero()}));
  EXPECT_FALSE(world.addGenerator(StiffSpring{a, Vec3(nan, 0, 0), 1.0, 0.0}));
  EXPECT_FALSE(world.removeGenerator(99999));
  EXPECT_FALSE(world.removeParticle(stale));
  WorldConfig config = world.config();
  config.dt = 0.0;
  EXPECT_FALSE(world.setConfig(config));
  config.dt = 0.01;
  config.substeps = 0;
  EXPECT_FALSE(world.setConfig(config));
  EXPECT_EQ(world.config().substeps, 2);

  EXPECT_EQ(world.stateHash(), before);
  EXPECT_EQ(world.generators().size(), generators);
  const Status message = world.removeParticle(stale);
  EXPECT_NE(message.message().find("stale"), std::string::npos) << message.message();
}

TEST(World, RemovingAParticleRemovesItsGenerators) {
  World world(configFor(Integrator::kRk4));
  buildScene(world);
  const std::size_t before = world.generators().size();
  const ParticleId first_link = world.particles().idAt(0);  // in two springs
  ASSERT_TRUE(world.removeParticle(first_link));
  EXPECT_EQ(world.generators().size(), before - 2);
  for (int i = 0; i < 100; ++i) world.step();
  EXPECT_EQ(world.divergenceCount(), 0u);
}

TEST(World, DivergenceIsDetectedInTheStepAndNamesTheParticle) {
  WorldConfig config;
  config.dt = 0.1;
  config.integrator = Integrator::kExplicitEuler;
  World world(config);
  ASSERT_TRUE(world.addParticle(particleAt(Vec3(5.0, 0.0, 0.0))));
  const ParticleId wild = *world.addParticle(particleAt(Vec3(1.0, 0.0, 0.0), 1e-6));
  // omega dt = sqrt(1e12) * 0.1: explicit Euler grows by ~1e5 per step and overflows quickly
  ASSERT_TRUE(world.addGenerator(Spring::anchoredAt(wild, Vec3::Zero(), 1e6, 0.0, 0.0)));
  std::uint64_t steps = 0;
  while (world.divergenceCount() == 0 && steps < 1000) {
    world.step();
    ++steps;
    if (world.divergenceCount() == 0) {
      ASSERT_TRUE(world.particles().positions().allFinite() &&
                  world.particles().velocities().allFinite());
    }
  }
  ASSERT_TRUE(world.lastDivergence().has_value());
  EXPECT_EQ(world.lastDivergence()->particle, wild);
  EXPECT_EQ(world.lastDivergence()->step, steps);
}

TEST(World, MomentumAndEnergyMeasurements) {
  WorldConfig config;
  config.gravity = Vec3(0.0, 0.0, -10.0);
  World world(config);
  ParticleSpec spec = particleAt(Vec3(0.0, 0.0, 2.0), 2.0);
  spec.velocity = Vec3(3.0, 0.0, 0.0);
  ASSERT_TRUE(world.addParticle(spec));
  ASSERT_TRUE(world.addParticle(particleAt(Vec3(0.0, 0.0, 5.0), 0.0)));  // immovable: no energy
  EXPECT_EQ(world.linearMomentum(), Vec3(6.0, 0.0, 0.0));
  EXPECT_DOUBLE_EQ(world.kineticEnergy(), 9.0);
  EXPECT_DOUBLE_EQ(world.gravitationalEnergy(), 40.0);  // m g h = 2 * 10 * 2
}

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
