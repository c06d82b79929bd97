// The engine at its numerical extremes (issue 5): stiff springs at and beyond each integrator's
// stability limit, the guard and divergence policies, mass ratios of 1:1e6, coordinates 1e6 m
// from the origin, dt from 1e-6 to 0.1 s, and momentum over 1e6 steps. Contact cases live with
// the contact tests.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "mass_aggregate_sim/engine/world/stability.h"
#include "mass_aggregate_sim/engine/world/world.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

const Integrator kExplicitFamily[] = {Integrator::kSemiImplicitEuler, Integrator::kPositionVerlet,
                                      Integrator::kVelocityVerlet, Integrator::kRk4};

// A particle of mass 1 on a spring of rest length 0 anchored at `anchor`, released 1 m along x
// from it: x(t) = cos(omega t) along x, energy omega^2 / 2.
struct Oscillator {
  World world;
  ParticleId particle;
  GeneratorId spring = 0;
};

Oscillator makeOscillator(const Integrator integrator, const Real omega, const Real dt,
                          const Vec3& anchor = Vec3::Zero()) {
  WorldConfig config;
  config.dt = dt;
  config.integrator = integrator;
  Oscillator o{World(config), {}, 0};
  ParticleSpec spec;
  spec.position = anchor + Vec3::UnitX();
  o.particle = o.world.addParticle(spec).value();
  Spring spring;
  spring.a = o.particle;
  spring.anchor = anchor;
  spring.stiffness = omega * omega;
  o.spring = o.world.addGenerator(spring).value();
  return o;
}

Real displacement(const Oscillator& o, const Vec3& anchor = Vec3::Zero()) {
  return o.world.particles().positions().col(0).x() - anchor.x();
}

TEST(StabilityLimits, MatchTheory) {
  EXPECT_EQ(stabilityLimit(Integrator::kExplicitEuler), 0.0);
  EXPECT_EQ(stabilityLimit(Integrator::kSemiImplicitEuler), 2.0);
  EXPECT_EQ(stabilityLimit(Integrator::kPositionVerlet), 2.0);
  EXPECT_EQ(stabilityLimit(Integrator::kVelocityVerlet), 2.0);
  EXPECT_DOUBLE_EQ(stabilityLimit(Integrator::kRk4), 2.0 * std::sqrt(2.0));
  EXPECT_TRUE(std::isinf(stabilityLimit(Integrator::kImplicitEuler)));
  // Explicit Euler with damping d: omega h <= sqrt(d^-h - 1).
  EXPECT_NEAR(stabilityLimit(Integrator::kExplicitEuler, 0.5, 0.1),
              std::sqrt(std::pow(0.5, -0.1) - 1.0), 1e-15);
}

TEST(StabilityGuard, FiresAtAndBeyondEachLimit) {
  const Real dt = 0.01;
  for (const Integrator integrator : kExplicitFamily) {
    const Real limit = stabilityLimit(integrator);
    for (const Real fraction : {0.9, 1.0, 1.1}) {
      const Real omega = fraction * limit / dt;
      Oscillator o = makeOscillator(integrator, omega, dt);
      const StabilityReport& report = o.world.stabilityReport();
      SCOPED_TRACE(std::string(integratorName(integrator)) + " at " + std::to_string(fraction));
      EXPECT_EQ(report.stable, fraction < 1.0);
      EXPECT_EQ(report.generator, o.spring);
      EXPECT_NEAR(report.omega, omega, 1e-9 * omega);
      EXPECT_NEAR(report.omega_h, fraction * limit, 1e-12);
      EXPECT_NEAR(report.stable_dt, limit / omega, 1e-12);
      EXPECT_EQ(report.substeps_needed, fraction < 1.0 ? 1 : 2);
      EXPECT_EQ(report.message.empty(), fraction < 1.0);
      if (fraction >= 1.0) {
        EXPECT_NE(report.message.find("spring " + std::to_string(o.spring)), std::string::npos);
      }
    }
  }
}

TEST(StabilityGuard, DynamicsAgreeWithTheLimits) {
  const Real dt = 0.01;
  for (const Integrator integrator : kExplicitFamily) {
    SCOPED_TRACE(integratorName(integrator));
    const Real limit = stabilityLimit(integrator);
    // Just inside: bounded for 5000 steps, and the energy guard stays silent.
    Oscillator inside = makeOscillator(integrator, 0.9 * limit / dt, dt);
    for (int s = 0; s < 5000; ++s) inside.world.step();
    EXPECT_LT(std::abs(displacement(inside)), 3.0);
    EXPECT_EQ(inside.world.divergenceCount(), 0u);
    // Just outside: the energy guard reports the particle long before anything overflows.
    Oscillator outside = makeOscillator(integrator, 1.1 * limit / dt, dt);
    int steps = 0;
    while (outside.world.divergenceCount() == 0 && steps < 500) {
      outside.world.step();
      ++steps;
    }
    ASSERT_EQ(outside.world.divergenceCount(), 1u);
    EXPECT_EQ(outside.world.lastDivergence()->particle, outside.particle);
    EXPECT_NE(outside.world.lastDivergence()->what.find("energy grew"), std::string::npos);
    EXPECT_TRUE(outside.world.particles().positions().allFinite());
  }
}

TEST(StabilityGuard, ExplicitEulerNeedsDamping) {
  Oscillator undamped = makeOscillator(Integrator::kExplicitEuler, 1.0, 0.001);
  EXPECT_FALSE(undamped.world.stabilityReport().stable);
  EXPECT_EQ(undamped.world.stabilityReport().substeps_needed, 0);  // no h is stable
  // Damping 0.5 per second, omega 10: stable while omega h <= sqrt(0.5^-h - 1), i.e. h < ~ln 2 /
  // 100.
  WorldConfig config;
  config.dt = 0.1;
  config.integrator = Integrator::kExplicitEuler;
  World world(config);
  ParticleSpec spec;
  spec.position = Vec3::UnitX();
  spec.damping = 0.5;
  const ParticleId id = world.addParticle(spec).value();
  Spring spring;
  spring.a = id;
  spring.stiffness = 100.0;
  world.addGenerator(spring);
  const StabilityReport report = world.stabilityReport();
  EXPECT_FALSE(report.stable);
  ASSERT_GT(report.substeps_needed, 1);
  const Real h = 0.1 / report.substeps_needed;
  EXPECT_LT(h, stabilityLimit(Integrator::kExplicitEuler, 0.5, h));
  config.substeps = report.substeps_needed;
  ASSERT_TRUE(world.setConfig(config));
  EXPECT_TRUE(world.stabilityReport().stable);
}

TEST(StabilityGuard, AutoSubstepKeepsAStiffSpringStable) {
  const Real dt = 0.01;
  Oscillator o = makeOscillator(Integrator::kSemiImplicitEuler, 5.0 / dt, dt);  // omega h = 5
  EXPECT_EQ(o.world.stabilityReport().substeps_needed, 3);
  WorldConfig config = o.world.config();
  config.auto_substep = true;
  ASSERT_TRUE(o.world.setConfig(config));
  for (int s = 0; s < 2000; ++s) o.world.step();
  EXPECT_EQ(o.world.substepsUsed(), 3);
  EXPECT_EQ(o.world.stabilityReport().substeps_used, 3);
  EXPECT_FALSE(o.world.stabilityReport().stable);  // the warning about dt itself remains
  EXPECT_EQ(o.world.divergenceCount(), 0u);
  // Semi-implicit Euler's orbit is an ellipse reaching 1 / sqrt(1 - (omega h / 2)^2) = 1.81.
  EXPECT_LT(std::abs(displacement(o)), 1.0 / std::sqrt(1.0 - std::pow(5.0 / 6.0, 2)) + 1e-9);
  // Without auto_substep the same scene runs away.
  Oscillator plain = makeOscillator(Integrator::kSemiImplicitEuler, 5.0 / dt, dt);
  for (int s = 0; s < 20; ++s) plain.world.step();
  EXPECT_GT(plain.world.divergenceCount(), 0u);
}

TEST(StabilityGuard, ImplicitEulerAndStiffSpringGeneratorStayStable) {
  const Real dt = 1.0 / 60.0;
  Oscillator implicit = makeOscillator(Integrator::kImplicitEuler, 100.0 / dt, dt);  // omega h 100
  EXPECT_TRUE(implicit.world.stabilityReport().stable);
  for (int s = 0; s < 1000; ++s) implicit.world.step();
  EXPECT_EQ(implicit.world.divergenceCount(), 0u);
  EXPECT_LT(std::abs(displacement(implicit)), 1.0);

  WorldConfig config;
  config.dt = dt;
  World world(config);
  ParticleSpec spec;
  spec.position = Vec3::UnitX();
  const ParticleId id = world.addParticle(spec).value();
  StiffSpring stiff;
  stiff.particle = id;
  stiff.stiffness = 1e8;  // omega h ~ 167 with semi-implicit Euler
  world.addGenerator(stiff);
  EXPECT_TRUE(world.stabilityReport().stable);
  for (int s = 0; s < 1000; ++s) world.step();
  EXPECT_EQ(world.divergenceCount(), 0u);
  EXPECT_LE(world.particles().positions().col(0).norm(), 1.0 + 1e-9);
}

TEST(StabilityGuard, ReportFollowsTheScene) {
  Oscillator o = makeOscillator(Integrator::kSemiImplicitEuler, 100.0, 0.01);  // omega h = 1
  EXPECT_TRUE(o.world.stabilityReport().stable);
  // A stiffer spring on a new particle takes over the report.
  ParticleSpec spec;
  spec.position = Vec3(0, 2, 0);
  const ParticleId other = o.world.addParticle(spec).value();
  Spring stiff;
  stiff.a = other;
  stiff.anchor = Vec3(0, 1, 0);
  stiff.stiffness = 300.0 * 300.0;  // omega h = 3
  const GeneratorId stiff_id = o.world.addGenerator(stiff).value();
  EXPECT_FALSE(o.world.stabilityReport().stable);
  EXPECT_EQ(o.world.stabilityReport().generator, stiff_id);
  // Moving or pushing particles changes nothing; substeps do.
  ASSERT_TRUE(o.world.setPosition(other, Vec3(0, 3, 0)));
  ASSERT_TRUE(o.world.addForce(other, Vec3(1, 0, 0)));
  EXPECT_FALSE(o.world.stabilityReport().stable);
  WorldConfig config = o.world.config();
  config.substeps = 2;
  ASSERT_TRUE(o.world.setConfig(config));
  EXPECT_TRUE(o.world.stabilityReport().stable);
  EXPECT_NEAR(o.world.stabilityReport().omega_h, 1.5, 1e-12);
  config.substeps = 1;
  ASSERT_TRUE(o.world.setConfig(config));
  ASSERT_TRUE(o.world.removeGenerator(stiff_id));
  EXPECT_TRUE(o.world.stabilityReport().stable);
  EXPECT_EQ(o.world.stabilityReport().generator, o.spring);
  // Removing the particle removes its spring: no spring left to report.
  ASSERT_TRUE(o.world.removeParticle(o.particle));
  EXPECT_EQ(o.world.stabilityReport().generator, 0u);
}

TEST(StabilityGuard, CoupledOmegaIsTheHighestModeOfAChain) {
  World world;
  std::vector<ParticleId> ids;
  for (int i = 0; i < 10; ++i) {
    ParticleSpec spec;
    spec.position = Vec3(i, 0, 0);
    ids.push_back(world.addParticle(spec).value());
  }
  for (int i = 1; i < 10; ++i) {
    Spring spring;
    spring.a = ids[i - 1];
    spring.b = ids[i];
    spring.stiffness = 100.0;
    spring.rest_length = 1.0;
    world.addGenerator(spring);
  }
  const StabilityReport& report = world.stabilityReport();
  EXPECT_NEAR(report.omega, std::sqrt(200.0), 1e-12);                // sqrt(k / (m/2))
  EXPECT_NEAR(report.coupled_omega, 2.0 * std::sqrt(100.0), 1e-12);  // 2 sqrt(k/m)
}

// An anchored spring whose omega h = 2.2 under semi-implicit Euler, for the policy tests.
Oscillator runaway(const DivergencePolicy policy) {
  Oscillator o = makeOscillator(Integrator::kSemiImplicitEuler, 220.0, 0.01);
  WorldConfig config = o.world.config();
  config.divergence_policy = policy;
  EXPECT_TRUE(o.world.setConfig(config));
  return o;
}

TEST(DivergencePolicy, PauseStopsSteppingUntilResumed) {
  Oscillator o = runaway(DivergencePolicy::kPause);
  int steps = 0;
  while (!o.world.paused() && steps < 100) {
    o.world.step();
    ++steps;
  }
  ASSERT_TRUE(o.world.paused());
  const std::uint64_t hash = o.world.stateHash();
  const std::uint64_t count = o.world.stepCount();
  o.world.step();
  EXPECT_EQ(o.world.advance(0.2), 0);
  EXPECT_EQ(o.world.stateHash(), hash);
  EXPECT_EQ(o.world.stepCount(), count);
  o.world.resume();
  o.world.step();
  EXPECT_EQ(o.world.stepCount(), count + 1);
}

TEST(DivergencePolicy, ResetRestoresTheSnapshot) {
  Oscillator o = runaway(DivergencePolicy::kReset);
  o.world.setResetSnapshot();
  const std::uint64_t snapshot_hash = o.world.stateHash();
  int steps = 0;
  while (o.world.divergenceCount() == 0 && steps < 100) {
    o.world.step();
    ++steps;
  }
  ASSERT_EQ(o.world.divergenceCount(), 1u);
  EXPECT_EQ(o.world.stateHash(), snapshot_hash);
  EXPECT_EQ(o.world.stepCount(), 0u);
  EXPECT_FALSE(o.world.paused());
  EXPECT_EQ(o.world.lastDivergence()->particle, o.particle);
  EXPECT_TRUE(o.world.hasResetSnapshot());
  // Without a snapshot, reset pauses.
  Oscillator bare = runaway(DivergencePolicy::kReset);
  for (int s = 0; s < 100 && !bare.world.paused(); ++s) bare.world.step();
  EXPECT_TRUE(bare.world.paused());
}

TEST(DivergencePolicy, NonFiniteValueIsReportedWithItsParticle) {
  WorldConfig config;
  config.energy_growth_limit = 0.0;  // only the finiteness check
  World world(config);
  ParticleSpec calm;
  world.addParticle(calm);
  ParticleSpec far;
  far.position = Vec3(1e200, 0, 0);
  const ParticleId id = world.addParticle(far).value();
  Spring spring;
  spring.a = id;
  spring.stiffness = 1e300;  // k x overflows to infinity
  world.addGenerator(spring);
  world.step();
  ASSERT_EQ(world.divergenceCount(), 1u);
  EXPECT_EQ(world.lastDivergence()->particle, id);
  EXPECT_EQ(world.lastDivergence()->step, 1u);
}

// With gravity alone the energy guard does not judge a step, and the semi-implicit Euler pass
// probes the state it writes instead of a pass after the step: an overflow is still reported in
// the step that made it, naming its particle, whether the particle is in one of the pass's groups
// of four or past the last one, and with one substep or several.
TEST(DivergencePolicy, AGravityOnlyOverflowIsReportedInTheStepThatMadeIt) {
  for (const Integrator integrator : allIntegrators()) {
    for (const int substeps : {1, 3}) {
      for (const std::size_t wild_index : {std::size_t{1}, std::size_t{4}}) {
        WorldConfig config;
        config.integrator = integrator;
        config.substeps = substeps;
        World world(config);
        ParticleId wild;
        for (std::size_t i = 0; i < 5; ++i) {
          ParticleSpec spec;
          spec.position = Vec3(0.0, static_cast<Real>(i), 0.0);
          if (i == wild_index) {
            // x + v h passes the largest double within the first step's first substep.
            spec.position.x() = 1.79e308;
            spec.velocity.x() = 1.7e308;
          }
          const ParticleId id = world.addParticle(spec).value();
          if (i == wild_index) wild = id;
        }
        world.step();
        const std::string label = std::to_string(static_cast<int>(integrator)) + " x " +
                                  std::to_string(substeps) + ", particle " +
                                  std::to_string(wild_index);
        ASSERT_EQ(world.divergenceCount(), 1u) << label;
        EXPECT_EQ(world.lastDivergence()->particle, wild) << label;
        EXPECT_EQ(world.lastDivergence()->step, 1u) << label;
      }
    }
  }
}

TEST(Extremes, MassRatioOfAMillionAcrossASpring) {
  WorldConfig config;
  config.dt = 1.0 / 600.0;
  World world(config);
  ParticleSpec heavy;
  heavy.inverse_mass = 1e-6;
  ParticleSpec light;
  light.position = Vec3(1.5, 0, 0);
  const ParticleId h = world.addParticle(heavy).value();
  const ParticleId l = world.addParticle(light).value();
  Spring spring;
  spring.a = h;
  spring.b = l;
  spring.stiffness = 100.0;
  spring.rest_length = 1.0;
  world.addGenerator(spring);
  // mu = m_h m_l / (m_h + m_l): the light particle sets omega.
  const Real omega = std::sqrt(100.0 * (1.0 + 1e-6));
  EXPECT_NEAR(world.stabilityReport().omega, omega, 1e-12);
  EXPECT_TRUE(world.stabilityReport().stable);
  // Period from the light particle's upward crossings of the rest length, over 10 s.
  std::vector<Real> crossings;
  Real previous = 0.5;
  for (int s = 0; s < 6000; ++s) {
    world.step();
    const auto x = world.particles().positions();
    const Real extension = (x.col(1) - x.col(0)).norm() - 1.0;
    if (previous < 0.0 && extension >= 0.0) crossings.push_back(world.time());
    previous = extension;
  }
  ASSERT_GE(crossings.size(), 10u);
  const Real period = (crossings.back() - crossings.front()) / (crossings.size() - 1);
  EXPECT_NEAR(period, 2.0 * M_PI / omega, 2e-3 * period);
  EXPECT_LT(world.linearMomentum().norm(), 1e-9);
  EXPECT_EQ(world.divergenceCount(), 0u);
  // The heavy end barely moves: it takes 1e-6 of the motion.
  EXPECT_LT(std::abs(world.particles().positions()(0, 0)), 1e-6);
}

TEST(Extremes, MillionMetresFromTheOrigin) {
  // The same oscillator at the origin and 1e6 m away along every axis. A double near 1e6 has a
  // spacing of 2^-33 m = 1.16e-10 m, so positions lose about 6 of their 16 significant digits;
  // the relative motion must agree to that spacing times the steps taken.
  const Vec3 far(1e6, 1e6, 1e6);
  Oscillator near_origin = makeOscillator(Integrator::kVelocityVerlet, 10.0, 0.01);
  Oscillator far_away = makeOscillator(Integrator::kVelocityVerlet, 10.0, 0.01, far);
  Real worst = 0.0;
  for (int s = 0; s < 1000; ++s) {
    near_origin.world.step();
    far_away.world.step();
    worst = std::max(worst, std::abs(displacement(near_origin) - displacement(far_away, far)));
  }
  char text[32];
  std::snprintf(text, sizeof(text), "%.3g", worst);
  RecordProperty("max_difference_m", text);
  EXPECT_GT(worst, 0.0);              // precision is really lost ...
  EXPECT_LT(worst, 1000 * 1.17e-10);  // ... but no more than the spacing per step
  EXPECT_LT(worst, 1e-7);
}

TEST(Extremes, TimeStepsFromAMicrosecondToATenthOfASecond) {
  // Undamped oscillator, omega = 1, run to t = 1 s: the error against cos(t) follows each
  // integrator's order; time stays exact.
  struct Case {
    Integrator integrator;
    int order;
  };
  const Case cases[] = {{Integrator::kSemiImplicitEuler, 1},
                        {Integrator::kVelocityVerlet, 2},
                        {Integrator::kRk4, 4},
                        {Integrator::kImplicitEuler, 1}};
  for (const Case& c : cases) {
    for (const Real dt : {1e-6, 1e-4, 1e-2, 0.1}) {
      SCOPED_TRACE(std::string(integratorName(c.integrator)) + " dt " + std::to_string(dt));
      Oscillator o = makeOscillator(c.integrator, 1.0, dt);
      const int steps = static_cast<int>(std::lround(1.0 / dt));
      for (int s = 0; s < steps; ++s) o.world.step();
      EXPECT_EQ(o.world.time(), steps * dt);
      const Real error = std::abs(displacement(o) - std::cos(1.0));
      EXPECT_LT(error, std::pow(dt, c.order) + 1e-9);
      EXPECT_EQ(o.world.divergenceCount(), 0u);
    }
  }
}

TEST(Extremes, MomentumConservedOverAMillionStepsInZeroGravity) {
  WorldConfig config;
  config.dt = 1e-3;
  World world(config);
  const Real inverse_masses[] = {1.0, 0.5, 2.0, 0.1};
  std::vector<ParticleId> ids;
  for (int i = 0; i < 4; ++i) {
    ParticleSpec spec;
    spec.position = Vec3(i, 0.3 * i * i, -0.2 * i);
    spec.velocity = Vec3(0.1 * i, -0.2, 0.05 * (3 - i));
    spec.inverse_mass = inverse_masses[i];
    ids.push_back(world.addParticle(spec).value());
  }
  for (int i = 0; i < 4; ++i) {
    Spring spring;
    spring.a = ids[i];
    spring.b = ids[(i + 1) % 4];
    spring.stiffness = 5.0 + i;
    spring.rest_length = 1.2;
    spring.damping = 0.1;
    world.addGenerator(spring);
  }
  const Vec3 momentum = world.linearMomentum();
  for (int s = 0; s < 1000000; ++s) world.step();
  EXPECT_LT((world.linearMomentum() - momentum).norm(), 1e-10 * momentum.norm());
  EXPECT_EQ(world.divergenceCount(), 0u);
}

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
