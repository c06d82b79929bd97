// Integrators against analytic solutions: measured order of convergence from halving dt, and the
// long-run energy behaviour of each on an undamped oscillator. Prints the figures it measures.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "mass_aggregate_sim/engine/world/world.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

struct Oscillator {
  Real mass = 1.0;
  Real stiffness = 4.0;  // omega = 2 rad/s
  Real damping = 0.0;    // dashpot coefficient c, N s/m
  Real x0 = 1.0;
  Real v0 = 0.0;

  // x(t) = e^(-beta t) (x0 cos(g t) + (v0 + beta x0) sin(g t) / g), beta = c/2m, g^2 = k/m - beta^2
  Real exact(const Real t) const {
    const Real beta = damping / (2.0 * mass);
    const Real g = std::sqrt(stiffness / mass - beta * beta);
    return std::exp(-beta * t) * (x0 * std::cos(g * t) + (v0 + beta * x0) * std::sin(g * t) / g);
  }
};

World makeOscillatorWorld(const Oscillator& o, const Integrator integrator, const Real dt) {
  WorldConfig config;
  config.dt = dt;
  config.integrator = integrator;
  World world(config);
  ParticleSpec spec;
  spec.position = Vec3(o.x0, 0.0, 0.0);
  spec.velocity = Vec3(o.v0, 0.0, 0.0);
  spec.inverse_mass = 1.0 / o.mass;
  const ParticleId p = *world.addParticle(spec);
  EXPECT_TRUE(world.addGenerator(Spring::anchoredAt(p, Vec3::Zero(), o.stiffness, 0.0, o.damping)));
  return world;
}

// Largest position error over [0, duration] against the exact solution.
Real oscillatorError(const Oscillator& o, const Integrator integrator, const int steps,
                     const Real duration) {
  World world = makeOscillatorWorld(o, integrator, duration / steps);
  Real worst = 0.0;
  for (int i = 0; i < steps; ++i) {
    world.step();
    worst = std::max(worst, std::abs(world.particles().positions()(0, 0) - o.exact(world.time())));
  }
  return worst;
}

// Steps for the coarse run of each integrator: fine enough to be in the asymptotic range, coarse
// enough that RK4's error stays far above round-off.
int coarseSteps(const Integrator integrator) {
  switch (integratorOrder(integrator)) {
    case 4:
      return 40;
    case 2:
      return 400;
    default:
      return 4000;
  }
}

Real measuredOrder(const Real coarse_error, const Real fine_error) {
  return std::log2(coarse_error / fine_error);
}

void expectOrderOnOscillator(const Oscillator& o, const char* label) {
  constexpr Real kDuration = 4.0;
  for (const Integrator integrator : allIntegrators()) {
    const int n = coarseSteps(integrator);
    const Real coarse = oscillatorError(o, integrator, n, kDuration);
    const Real fine = oscillatorError(o, integrator, 2 * n, kDuration);
    const Real order = measuredOrder(coarse, fine);
    std::printf(
        "[ order ] %-8s %-20s dt=%-9.3g err=%-10.3e dt/2 err=%-10.3e order=%.3f (theory %d)\n",
        label, integratorName(integrator), kDuration / n, coarse, fine, order,
        integratorOrder(integrator));
    EXPECT_NEAR(order, integratorOrder(integrator), 0.2) << integratorName(integrator);
  }
}

TEST(IntegratorConvergence, UndampedHarmonicOscillator) {
  expectOrderOnOscillator(Oscillator{}, "undamped");
}

TEST(IntegratorConvergence, DampedHarmonicOscillator) {
  Oscillator o;
  o.damping = 0.8;  // beta = 0.4 s^-1, underdamped
  expectOrderOnOscillator(o, "damped");
}

TEST(IntegratorConvergence, ProjectileWithoutDrag) {
  // x(t) = x0 + v0 t + g t^2 / 2. First-order methods err by g t dt / 2 (order 1); Verlet and RK4
  // integrate a constant acceleration exactly.
  const Vec3 gravity(0.0, 0.0, -9.81);
  const Vec3 x0(0.0, 0.0, 1.5);
  const Vec3 v0(20.0, 0.0, 15.0);
  constexpr Real kDuration = 3.0;
  const auto error = [&](const Integrator integrator, const int steps) {
    WorldConfig config;
    config.dt = kDuration / steps;
    config.integrator = integrator;
    config.gravity = gravity;
    World world(config);
    ParticleSpec spec;
    spec.position = x0;
    spec.velocity = v0;
    EXPECT_TRUE(world.addParticle(spec).isOk());
    for (int i = 0; i < steps; ++i) world.step();
    const Vec3 exact = x0 + v0 * kDuration + 0.5 * gravity * kDuration * kDuration;
    return (world.particles().positions().col(0) - exact).norm();
  };
  for (const Integrator integrator : allIntegrators()) {
    const Real coarse = error(integrator, 300);
    const Real fine = error(integrator, 600);
    if (integratorOrder(integrator) == 1) {
      const Real order = measuredOrder(coarse, fine);
      std::printf("[ order ] %-8s %-20s err=%-10.3e dt/2 err=%-10.3e order=%.3f (theory 1)\n",
                  "project.", integratorName(integrator), coarse, fine, order);
      EXPECT_NEAR(order, 1.0, 0.2) << integratorName(integrator);
    } else {
      std::printf("[ order ] %-8s %-20s err=%-10.3e dt/2 err=%-10.3e (exact for constant a)\n",
                  "project.", integratorName(integrator), coarse, fine);
      EXPECT_LT(coarse, 1e-9) << integratorName(integrator);
      EXPECT_LT(fine, 1e-9) << integratorName(integrator);
    }
  }
}

// Relative energy error |E - E0| / E0 of the undamped oscillator, largest over each tenth of the
// run.
std::vector<Real> energyErrorByTenth(const Integrator integrator, const int steps, const Real dt) {
  World world = makeOscillatorWorld(Oscillator{}, integrator, dt);
  const Real e0 = world.totalEnergy();
  std::vector<Real> worst(10, 0.0);
  for (int i = 0; i < steps; ++i) {
    world.step();
    const Real relative = std::abs(world.totalEnergy() - e0) / e0;
    auto& slot = worst[static_cast<std::size_t>(10 * i / steps)];
    slot = std::max(slot, relative);
  }
  return worst;
}

TEST(IntegratorEnergy, SymplecticIntegratorsKeepOscillatorEnergyBoundedOver1e5Steps) {
  constexpr int kSteps = 100000;
  constexpr Real kDt = 0.01;  // omega dt = 0.02, 318 periods
  for (const Integrator integrator :
       {Integrator::kSemiImplicitEuler, Integrator::kPositionVerlet, Integrator::kVelocityVerlet}) {
    const std::vector<Real> worst = energyErrorByTenth(integrator, kSteps, kDt);
    std::printf("[ energy ] %-20s max |dE|/E0 first tenth %.3e, last tenth %.3e\n",
                integratorName(integrator), worst.front(), worst.back());
    // Bounded: no growth from the first tenth of the run to the last, and small throughout.
    EXPECT_LT(worst.back(), 1.05 * worst.front()) << integratorName(integrator);
    EXPECT_LT(*std::max_element(worst.begin(), worst.end()), 0.02) << integratorName(integrator);
  }
}

TEST(IntegratorEnergy, ExplicitEulerEnergyGrowsAndImplicitEulerDecays) {
  constexpr int kSteps = 100000;
  constexpr Real kDt = 0.01;
  const auto run = [&](const Integrator integrator) {
    World world = makeOscillatorWorld(Oscillator{}, integrator, kDt);
    const Real e0 = world.totalEnergy();
    for (int i = 0; i < kSteps; ++i) world.step();
    return world.totalEnergy() / e0;
  };
  const Real explicit_ratio = run(Integrator::kExplicitEuler);
  const Real implicit_ratio = run(Integrator::kImplicitEuler);
  const Real rk4_ratio = run(Integrator::kRk4);
  std::printf("[ energy ] E(1e5 steps)/E0: explicit_euler %.4e, implicit_euler %.4e, rk4 %.10f\n",
              explicit_ratio, implicit_ratio, rk4_ratio);
  // Each explicit step multiplies the energy by 1 + (omega dt)^2: (1.0004)^1e5 ~ e^40.
  EXPECT_GT(explicit_ratio, 1e10);
  EXPECT_NEAR(std::log(explicit_ratio), kSteps * std::log1p(0.02 * 0.02), 1e-3 * 40.0);
  // Each backward step divides it by 1 + (omega dt)^2.
  EXPECT_LT(implicit_ratio, 1e-10);
  // RK4 loses energy slowly, by (omega dt)^6 / 72 per step.
  EXPECT_NEAR(rk4_ratio, 1.0, 1e-4);
}

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
