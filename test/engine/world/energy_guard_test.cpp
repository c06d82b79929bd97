// The energy guard against each integrator's own energy swing: the swing formulas agree with the
// integrators, no bounded orbit below an integrator's limit ever trips the guard (the cases that
// used to: semi-implicit Euler from omega h = 1.818, position Verlet from 1.648, auto_substep
// pausing a stable stiff spring), and real divergence is still caught.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "../integrators/integrator_params.h"
#include "mass_aggregate_sim/engine/world/stability.h"
#include "mass_aggregate_sim/engine/world/world.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

constexpr Real kDt = 0.01;

// A 1 kg particle on an anchored spring of rest length 0 with omega h = `omega_h`, started at
// phase `phase` of the orbit (x = cos, v = -omega sin), no damping unless given.
World oscillator(const Integrator integrator, const Real omega_h, const Real phase,
                 const Real energy_growth_limit = 10.0, const Real damping = 1.0,
                 const DivergencePolicy policy = DivergencePolicy::kContinue) {
  WorldConfig config;
  config.dt = kDt;
  config.integrator = integrator;
  config.energy_growth_limit = energy_growth_limit;
  config.divergence_policy = policy;
  World world(config);
  const Real omega = omega_h / kDt;
  ParticleSpec spec;
  spec.position = Vec3(std::cos(phase), 0.0, 0.0);
  spec.velocity = Vec3(-omega * std::sin(phase), 0.0, 0.0);
  spec.damping = damping;
  const ParticleId p = world.addParticle(spec).value();
  EXPECT_TRUE(world.addGenerator(Spring::anchoredAt(p, Vec3::Zero(), omega * omega, 0.0, 0.0)));
  return world;
}

const Integrator kSymplectic[] = {Integrator::kSemiImplicitEuler, Integrator::kPositionVerlet,
                                  Integrator::kVelocityVerlet};

// The ratio of the largest to the smallest energy an integrator reports along one orbit, over
// 20,000 steps (the rotation per step is no simple fraction of a turn at these omega h, so the
// steps come close to every point of the orbit).
Real measuredSwing(const Integrator integrator, const Real omega_h) {
  World world = oscillator(integrator, omega_h, 0.3, 0.0);
  world.step();  // position Verlet reports its own velocity from the first step on
  Real largest = 0.0;
  Real smallest = std::numeric_limits<Real>::infinity();
  for (int i = 0; i < 20000; ++i) {
    world.step();
    const Real energy = world.kineticEnergy() + world.springEnergy();
    largest = std::max(largest, energy);
    smallest = std::min(smallest, energy);
  }
  return largest / smallest;
}

TEST(EnergySwing, FormulasBoundAndReachWhatTheIntegratorsDo) {
  for (const Integrator integrator : kSymplectic) {
    for (const Real omega_h : {0.3, 0.97, 1.5, 1.8, 1.9, 1.97}) {
      const Real formula = energySwing(integrator, omega_h);
      const Real measured = measuredSwing(integrator, omega_h);
      std::printf("[ energy ] swing %-20s omega h %-5.3g formula %-9.4g measured %.4g\n",
                  integratorName(integrator), omega_h, formula, measured);
      EXPECT_LE(measured, formula * (1.0 + 1e-9)) << integratorName(integrator) << " " << omega_h;
      EXPECT_GE(measured, 1.0 + 0.95 * (formula - 1.0))
          << integratorName(integrator) << " " << omega_h;
    }
  }
  for (const Integrator integrator :
       {Integrator::kExplicitEuler, Integrator::kRk4, Integrator::kImplicitEuler}) {
    EXPECT_EQ(energySwing(integrator, 0.0), 1.0);
  }
  EXPECT_EQ(energySwing(Integrator::kRk4, 2.5), 1.0);
  EXPECT_TRUE(std::isinf(energySwing(Integrator::kSemiImplicitEuler, 2.0)));
  EXPECT_EQ(energySwing(Integrator::kExplicitEuler, 0.1), 1.0);
  EXPECT_EQ(energySwing(Integrator::kImplicitEuler, 100.0), 1.0);
}

// Each integrator's bounded orbits just below its limit, from many phases, with the default
// guard: never a divergence.
TEST(EnergyGuard, NoBoundedOrbitBelowTheLimitTripsIt) {
  for (const Integrator integrator :
       {Integrator::kSemiImplicitEuler, Integrator::kPositionVerlet, Integrator::kVelocityVerlet,
        Integrator::kRk4, Integrator::kImplicitEuler}) {
    const Real limit = stabilityLimit(integrator);
    for (const Real omega_h : {0.5, 1.648, 1.818, std::isinf(limit) ? 50.0 : 0.99 * limit}) {
      if (omega_h >= limit) continue;
      for (int k = 0; k < 8; ++k) {
        World world = oscillator(integrator, omega_h, 0.39 * k);
        for (int i = 0; i < 2000; ++i) world.step();
        EXPECT_EQ(world.divergenceCount(), 0u)
            << integratorName(integrator) << " omega h " << omega_h << " phase " << k << ": "
            << (world.lastDivergence() ? world.lastDivergence()->what : "");
      }
    }
  }
  // Explicit Euler is bounded only with damping: d = 0.5 per second at omega h = 0.05 keeps
  // d^h (1 + (omega h)^2) < 1.
  const Real h_limit = stabilityLimit(Integrator::kExplicitEuler, 0.5, kDt);
  ASSERT_GT(h_limit, 0.05);
  for (int k = 0; k < 8; ++k) {
    World world = oscillator(Integrator::kExplicitEuler, 0.05, 0.39 * k, 10.0, 0.5);
    for (int i = 0; i < 2000; ++i) world.step();
    EXPECT_EQ(world.divergenceCount(), 0u) << "explicit Euler, damped, phase " << k;
  }
}

TEST(EnergyGuard, AutoSubstepLeavesAMarginAndNeverPausesAStableStiffSpring) {
  // k = 1e6 N/m on 1 kg at 60 Hz: omega dt = 16.7. The fewest stable substeps (9: omega h 1.852)
  // swing the energy 27-fold; auto_substep keeps omega h <= 0.9 of the limit instead.
  for (const Integrator integrator : kSymplectic) {
    WorldConfig config;
    config.dt = 1.0 / 60.0;
    config.integrator = integrator;
    config.auto_substep = true;
    config.divergence_policy = DivergencePolicy::kPause;
    World world(config);
    ParticleSpec spec;
    spec.position = Vec3(0.0, 0.0, 0.01);
    spec.velocity = Vec3(1.0, 0.0, 0.0);
    const ParticleId p = world.addParticle(spec).value();
    ASSERT_TRUE(world.addGenerator(Spring::anchoredAt(p, Vec3::Zero(), 1e6, 0.0, 0.0)));
    const StabilityReport& report = world.stabilityReport();
    EXPECT_EQ(report.substeps_needed, 9) << integratorName(integrator);
    EXPECT_EQ(report.substeps_used, 10) << integratorName(integrator);
    EXPECT_LE(1000.0 / 60.0 / report.substeps_used, kAutoSubstepMargin * 2.0);
    for (int i = 0; i < 600; ++i) world.step();
    EXPECT_EQ(world.divergenceCount(), 0u) << integratorName(integrator);
    EXPECT_FALSE(world.paused()) << integratorName(integrator);
    EXPECT_EQ(world.stepCount(), 600u);
  }
}

// The first step at which the guard reports, or -1.
int firstDivergence(World& world, const int steps) {
  for (int i = 0; i < steps; ++i) {
    world.step();
    if (world.divergenceCount() > 0) return i + 1;
  }
  return -1;
}

TEST(EnergyGuard, StillCatchesExplicitEulerRunningAway) {
  // Undamped explicit Euler multiplies the energy by 1 + (omega h)^2 every step: the default
  // guard (energy 11 times its reference) fires after ln(11) / ln(1 + (omega h)^2) steps, plus
  // the reference step.
  for (const Real omega_h : {0.05, 0.5}) {
    World world = oscillator(Integrator::kExplicitEuler, omega_h, 0.0);
    const int expected =
        static_cast<int>(std::ceil(std::log(11.0) / std::log1p(omega_h * omega_h))) + 1;
    const int fired = firstDivergence(world, 2000);
    std::printf("[ energy ] explicit Euler omega h %.2f: guard fired at step %d (expected %d)\n",
                omega_h, fired, expected);
    EXPECT_GT(fired, 0);
    EXPECT_LE(fired, expected + 1);
    EXPECT_GE(fired, expected - 2);
  }
}

TEST(EnergyGuard, CatchesEveryIntegratorBeyondItsLimit) {
  for (const Integrator integrator : kSymplectic) {
    World world = oscillator(integrator, 1.1 * stabilityLimit(integrator), 0.0);
    const int fired = firstDivergence(world, 200);
    EXPECT_GT(fired, 0) << integratorName(integrator);
    EXPECT_LE(fired, 40) << integratorName(integrator);
  }
  World rk4 = oscillator(Integrator::kRk4, 1.1 * stabilityLimit(Integrator::kRk4), 0.0);
  EXPECT_GT(firstDivergence(rk4, 400), 0);
}

TEST(EnergyGuard, NonFiniteIsCaughtInTheStepThatMadeIt) {
  for (const Integrator integrator : allIntegrators()) {
    World world = oscillator(integrator, 0.5, 0.0);
    for (int i = 0; i < 5; ++i) world.step();
    ASSERT_EQ(world.divergenceCount(), 0u);
    const ParticleId p = world.particles().idAt(0);
    // k (l - L) = 1e308 * 100 overflows to infinity.
    ASSERT_TRUE(world.addGenerator(Spring::anchoredAt(p, Vec3(100.0, 0.0, 0.0), 1e308, 0.0, 0.0)));
    world.step();
    EXPECT_GE(world.divergenceCount(), 1u) << integratorName(integrator);
    ASSERT_TRUE(world.lastDivergence().has_value());
    EXPECT_EQ(world.lastDivergence()->step, 6u) << integratorName(integrator);
  }
}

// The energy guard judges only steps in which no contact or link acted; a particle faster than
// CollisionSettings::runaway_speed after such a step is the divergence there. Free flight is not
// judged, at any speed.
TEST(RunawayGuard, AParticleTooFastAfterContactsIsReported) {
  WorldConfig config;
  config.gravity = Vec3(0.0, 0.0, -9.81);
  ParticleSpec spec;
  spec.position = Vec3(0.0, 0.0, 0.1);
  spec.radius = 0.1;
  World flight(config);
  const ParticleId flying = *flight.addParticle(spec);
  ASSERT_TRUE(flight.setVelocity(flying, Vec3(2e4, 0.0, 0.0)));
  flight.step();
  EXPECT_EQ(flight.divergenceCount(), 0u);

  World world(config);
  ASSERT_TRUE(world.addCollider(PlaneCollider{Vec3::UnitZ(), 0.0, Material{0.0, 0.0}}));
  const ParticleId sliding = *world.addParticle(spec);
  for (int i = 0; i < 5; ++i) world.step();
  ASSERT_GT(world.lastContactStats().contacts, 0u);
  ASSERT_TRUE(world.setVelocity(sliding, Vec3(9e3, 0.0, 0.0)));
  world.step();
  EXPECT_EQ(world.divergenceCount(), 0u);
  ASSERT_TRUE(world.setVelocity(sliding, Vec3(2e4, 0.0, 0.0)));
  world.step();
  ASSERT_EQ(world.divergenceCount(), 1u);
  EXPECT_EQ(world.lastDivergence()->particle, sliding);
  EXPECT_NE(world.lastDivergence()->what.find("runaway speed"), std::string::npos);
  // A higher limit lets it go.
  CollisionSettings settings = world.collisionSettings();
  settings.runaway_speed = 1e5;
  ASSERT_TRUE(world.setCollisionSettings(settings));
  world.step();
  EXPECT_EQ(world.divergenceCount(), 1u);
  settings.runaway_speed = 0.0;
  EXPECT_FALSE(world.setCollisionSettings(settings));
  settings.runaway_speed = std::nan("");
  EXPECT_FALSE(world.setCollisionSettings(settings));
}

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
