// Drags in the stability report (stability.h): each integrator's decay limit is where a dragged
// particle's velocity turns from decaying to growing, a drag beyond it is named with the substeps
// it needs, auto_substep takes them, and the bodies' linear and angular drags are held to
// semi-implicit Euler's limit at the bodies' substeps.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "mass_aggregate_sim/engine/world/stability.h"
#include "mass_aggregate_sim/engine/world/world.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

constexpr Real kDt = 0.01;

// A 1 kg particle moving at 1 m/s with no gravity under a drag of rate `rate` (k1 = rate).
struct Dragged {
  World world;
  GeneratorId drag = 0;
};

Dragged dragged(const Integrator integrator, const Real rate, const bool auto_substep = false) {
  WorldConfig config;
  config.dt = kDt;
  config.gravity = Vec3::Zero();
  config.integrator = integrator;
  config.auto_substep = auto_substep;
  Dragged d{World(config), 0};
  ParticleSpec spec;
  spec.velocity = Vec3(1.0, 0.0, 0.0);
  const ParticleId id = *d.world.addParticle(spec);
  d.drag = *d.world.addGenerator(Drag{id, rate, 0.0});
  return d;
}

Real speedAfter(World& world, const int steps) {
  for (int i = 0; i < steps; ++i) world.step();
  return world.particles().velocities().col(0).norm();
}

TEST(DragStability, EachIntegratorsLimitIsWhereADraggedParticleTurns) {
  for (const Integrator integrator : allIntegrators()) {
    const Real limit = decayLimit(integrator);
    const char* name = integratorName(integrator);
    if (std::isinf(limit)) {
      Dragged d = dragged(integrator, 1e6 / kDt);
      EXPECT_TRUE(d.world.stabilityReport().stable) << name;
      EXPECT_LT(speedAfter(d.world, 100), 1e-3) << name;
      continue;
    }
    Dragged below = dragged(integrator, 0.97 * limit / kDt);
    EXPECT_TRUE(below.world.stabilityReport().stable) << name;
    EXPECT_LT(speedAfter(below.world, 2000), 1.0) << name;
    Dragged beyond = dragged(integrator, 1.03 * limit / kDt);
    const StabilityReport report = beyond.world.stabilityReport();
    EXPECT_FALSE(report.stable) << name;
    EXPECT_EQ(report.generator, beyond.drag) << name;
    EXPECT_NEAR(report.omega_h, 1.03 * limit, 1e-12) << name;
    EXPECT_EQ(report.substeps_needed, 2) << name;
    const Real speed = speedAfter(beyond.world, 2000);
    EXPECT_TRUE(!std::isfinite(speed) || speed > 1.0) << name << ": " << speed;
  }
}

TEST(DragStability, AStrongDragIsNamedAndAutoSubstepTakesWhatItNeeds) {
  // k1 = 3000 N s/m on 1 kg at dt = 0.01 s: rate h = 30 against semi-implicit Euler's 2; stable
  // for h < 2 / 3000 s, 16 substeps; auto_substep keeps 0.9 of the limit: 17.
  Dragged strong = dragged(Integrator::kSemiImplicitEuler, 3000.0);
  const StabilityReport report = strong.world.stabilityReport();
  ASSERT_FALSE(report.stable);
  EXPECT_EQ(report.substeps_needed, 16);
  EXPECT_EQ(report.substeps_with_margin, 17);
  EXPECT_EQ(report.message.rfind("drag " + std::to_string(strong.drag) +
                                     " is unstable with semi_implicit_euler: rate*h = 30 ",
                                 0),
            0u)
      << report.message;
  const Real runaway = speedAfter(strong.world, 400);
  EXPECT_TRUE(!std::isfinite(runaway) || runaway > 1.0) << runaway;
  Dragged tamed = dragged(Integrator::kSemiImplicitEuler, 3000.0, true);
  EXPECT_EQ(tamed.world.stabilityReport().substeps_used, 17);
  EXPECT_LT(speedAfter(tamed.world, 10), 1e-12);
}

// A 1 kg unit cube (I = 1/6 kg m^2) spinning and moving at 1 (m or rad)/s, without gravity or
// damping, under a drag of k1 and angular.
struct DraggedBody {
  World world;
  BodyId body;
  GeneratorId drag = 0;
};

DraggedBody draggedBody(const Real k1, const Real angular, const bool auto_substep = false) {
  WorldConfig config;
  config.dt = 1.0 / 60.0;
  config.gravity = Vec3::Zero();
  config.auto_substep = auto_substep;
  DraggedBody d{World(config), BodyId{}, 0};
  BodySpec spec;
  BodyShapeSpec cube;
  cube.geometry = BoxShape{Vec3::Constant(0.5)};
  spec.shapes = {cube};
  spec.mass = 1.0;
  spec.linear_velocity = Vec3(1.0, 0.0, 0.0);
  spec.angular_velocity = Vec3(0.0, 0.0, 1.0);
  spec.can_sleep = false;
  d.body = *d.world.addBody(spec);
  BodyDrag drag;
  drag.body = d.body;
  drag.k1 = k1;
  drag.angular = angular;
  d.drag = *d.world.addBodyGenerator(drag);
  return d;
}

TEST(DragStability, ABodysLinearAndAngularDragsAreHeldToTheBodiesLimit) {
  // At the bodies' 4 substeps, h = 1/240 s: rate h < 2 for rate < 480 1/s. Linear k1 = 0.97 and
  // 1.03 times 480 on 1 kg; angular 0.97 and 1.03 times 80 on I = 1/6 (rate 6 angular).
  const Real h = 1.0 / 240.0;
  const auto run = [](DraggedBody& d) {
    for (int i = 0; i < 300; ++i) d.world.step();
    const std::size_t i = *d.world.bodies().find(d.body);
    return Vec3(d.world.bodies().linearVelocity(i).norm(),
                d.world.bodies().angularVelocity(i).norm(), 0.0);
  };
  DraggedBody below = draggedBody(0.97 * 2.0 / h, 0.97 * 2.0 / h / 6.0);
  EXPECT_TRUE(below.world.stabilityReport().stable) << below.world.stabilityReport().message;
  const Vec3 slowed = run(below);
  EXPECT_LT(slowed.x(), 1.0);
  EXPECT_LT(slowed.y(), 1.0);

  DraggedBody linear = draggedBody(1.03 * 2.0 / h, 0.0);
  const StabilityReport linear_report = linear.world.stabilityReport();
  EXPECT_FALSE(linear_report.stable);
  EXPECT_EQ(linear_report.generator, linear.drag);
  EXPECT_NEAR(linear_report.omega_h, 2.06, 1e-12);
  EXPECT_EQ(linear_report.message.rfind("drag ", 0), 0u) << linear_report.message;
  EXPECT_NE(linear_report.message.find("(the bodies' integrator)"), std::string::npos);
  EXPECT_GT(run(linear).x(), 1.0);

  DraggedBody angular = draggedBody(0.0, 1.03 * 2.0 / h / 6.0);
  const StabilityReport angular_report = angular.world.stabilityReport();
  EXPECT_FALSE(angular_report.stable);
  EXPECT_EQ(angular_report.message.rfind("angular drag ", 0), 0u) << angular_report.message;
  EXPECT_GT(run(angular).y(), 1.0);

  // auto_substep takes the 5 substeps the angular one needs with its margin.
  DraggedBody tamed = draggedBody(0.0, 1.03 * 2.0 / h / 6.0, true);
  EXPECT_EQ(tamed.world.stabilityReport().substeps_used, 5);
  EXPECT_LT(run(tamed).y(), 1e-6);
}

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
