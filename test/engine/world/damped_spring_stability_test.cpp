// Damped springs in the stability report (largestStableDampedSubstep): a spring's damping c on its
// line shrinks the step its integrator can take (a critically damped one is stable under
// semi-implicit Euler only while omega h <= 2 sqrt(2) - 2), and the report now says where a
// damped oscillator turns from decaying to growing, for particles and for springs on bodies.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "mass_aggregate_sim/engine/world/stability.h"
#include "mass_aggregate_sim/engine/world/world.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

constexpr Real kDt = 0.01;

// A 1 kg particle 1 m from the anchor of a spring of rest length 0, stiffness omega^2 and
// damping 2 zeta omega, one substep of kDt, no gravity.
World dampedOscillator(const Integrator integrator, const Real omega, const Real zeta,
                       const bool auto_substep = false) {
  WorldConfig config;
  config.dt = kDt;
  config.gravity = Vec3::Zero();
  config.integrator = integrator;
  config.auto_substep = auto_substep;
  World world(config);
  ParticleSpec spec;
  spec.position = Vec3(1.0, 0.0, 0.0);
  const ParticleId id = *world.addParticle(spec);
  world.addGenerator(Spring::anchoredAt(id, Vec3::Zero(), omega * omega, 0.0, 2.0 * zeta * omega));
  return world;
}

Real distanceAfter(World& world, const int steps) {
  for (int i = 0; i < steps; ++i) world.step();
  return world.particles().positions().col(0).norm();
}

TEST(DampedSpringStability, TheLimitIsWhereADampedOscillatorTurns) {
  for (const Integrator integrator : {Integrator::kSemiImplicitEuler, Integrator::kPositionVerlet,
                                      Integrator::kVelocityVerlet, Integrator::kRk4}) {
    for (const Real zeta : {0.5, 1.0, 2.0}) {
      // omega h at the limit, for this zeta: h* at omega = 1.
      const Real limit = largestStableDampedSubstep(integrator, 1.0, 2.0 * zeta, 1.0);
      const std::string what =
          std::string(integratorName(integrator)) + " zeta " + std::to_string(zeta);
      World below = dampedOscillator(integrator, 0.97 * limit / kDt, zeta);
      EXPECT_TRUE(below.stabilityReport().stable) << what;
      EXPECT_LT(distanceAfter(below, 3000), 1.0) << what;
      World beyond = dampedOscillator(integrator, 1.03 * limit / kDt, zeta);
      const StabilityReport report = beyond.stabilityReport();
      EXPECT_FALSE(report.stable) << what;
      EXPECT_EQ(report.substeps_needed, 2) << what;
      EXPECT_NEAR(report.limit, limit, 1e-6 * limit) << what;  // RK4: by bisection
      EXPECT_NEAR(report.damping_rate, 2.0 * zeta * 1.03 * limit / kDt, 1e-6) << what;
      const Real distance = distanceAfter(beyond, 3000);
      EXPECT_TRUE(!std::isfinite(distance) || distance > 1.0) << what << ": " << distance;
    }
  }
  // Closed forms: semi-implicit Euler (omega h)^2 + 2 gamma h = 4, the Verlets + 4 gamma h.
  EXPECT_NEAR(largestStableDampedSubstep(Integrator::kSemiImplicitEuler, 1.0, 2.0, 1.0),
              2.0 * std::sqrt(2.0) - 2.0, 1e-15);
  EXPECT_NEAR(largestStableDampedSubstep(Integrator::kVelocityVerlet, 1.0, 2.0, 1.0),
              2.0 * (std::sqrt(5.0) - 2.0), 1e-15);
  // Undamped, the same as before; RK4 overdamped, its real-axis limit on the fast root.
  EXPECT_EQ(largestStableDampedSubstep(Integrator::kSemiImplicitEuler, 3.0, 0.0, 1.0),
            largestStableSubstep(Integrator::kSemiImplicitEuler, 3.0, 1.0));
  EXPECT_NEAR(largestStableDampedSubstep(Integrator::kRk4, 0.0, 4.0, 1.0),
              decayLimit(Integrator::kRk4) / 4.0, 1e-12);
  EXPECT_TRUE(std::isinf(largestStableDampedSubstep(Integrator::kImplicitEuler, 1e6, 1e6, 1.0)));
}

TEST(DampedSpringStability, ACriticallyDampedSpringIsNamedAndAutoSubstepTamesIt) {
  // omega h = 1 with zeta = 1: within the undamped limit 2, beyond the damped 0.83. Before the
  // damping counted, the report called it stable and it ran away.
  World world = dampedOscillator(Integrator::kSemiImplicitEuler, 1.0 / kDt, 1.0);
  const StabilityReport report = world.stabilityReport();
  ASSERT_FALSE(report.stable);
  EXPECT_NE(report.message.find("damping c/mu 200 1/s"), std::string::npos) << report.message;
  EXPECT_NE(report.message.find("exceeds the limit 0.8284"), std::string::npos) << report.message;
  const Real runaway = distanceAfter(world, 2000);
  EXPECT_TRUE(!std::isfinite(runaway) || runaway > 1.0) << runaway;
  World tamed = dampedOscillator(Integrator::kSemiImplicitEuler, 1.0 / kDt, 1.0, true);
  EXPECT_EQ(tamed.stabilityReport().substeps_used, 2);  // 0.9 of 0.83 per substep: 1 / 0.75
  EXPECT_LT(distanceAfter(tamed, 2000), 1e-6);
}

TEST(DampedSpringStability, ADampedSpringOnABodyIsHeldToTheBodiesDampedLimit) {
  // A 1 kg ball on a critically damped spring to the world at the bodies' 4 substeps of 1/240 s:
  // omega = 1.03 and 0.97 times 0.8284 / h.
  const Real h = 1.0 / 240.0;
  const Real limit = 2.0 * std::sqrt(2.0) - 2.0;
  for (const Real factor : {0.97, 1.03}) {
    WorldConfig config;
    config.dt = 1.0 / 60.0;
    config.gravity = Vec3::Zero();
    World world(config);
    BodySpec spec;
    BodyShapeSpec ball;
    ball.geometry = SphereShape{0.1};
    spec.shapes = {ball};
    spec.mass = 1.0;
    spec.pose.position = Vec3(1.0, 0.0, 0.0);
    spec.can_sleep = false;
    const BodyId id = *world.addBody(spec);
    const Real omega = factor * limit / h;
    ASSERT_TRUE(world.addBodyGenerator(PointSpring::between(
        JointEnd::onBody(id), JointEnd::inWorld(Vec3::Zero()), omega * omega, 0.0, 2.0 * omega)));
    EXPECT_EQ(world.stabilityReport().stable, factor < 1.0) << factor;
    for (int i = 0; i < 300; ++i) world.step();
    const Real distance = world.bodies().position(*world.bodies().find(id)).norm();
    if (factor < 1.0) {
      EXPECT_LT(distance, 1.0) << factor;
    } else {
      EXPECT_TRUE(!std::isfinite(distance) || distance > 1.0) << factor << ": " << distance;
    }
  }
}

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
