// Free rigid-body motion (issue 14's acceptance tests 1-3): torque-free spin conserves angular
// momentum and energy, the intermediate axis flips (and does not without the gyroscopic term),
// free fall with spin follows the closed form; the exponential map against the seeds' first-order
// quaternion update.
#include "engine/bodies/body_motion.h"

#include <gtest/gtest.h>

#include <cmath>

#include "body_scenes.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

using namespace test_bodies;

// A body of principal inertia (1, 2, 3) kg m^2: a 12 kg box sqrt(2) x 1 m and (almost) no thickness
// (I = m (b^2 + c^2) / 12 ...).
BodySpec inertia123(const Vec3& w) {
  BodySpec spec = body(box(Vec3(0.5 * std::sqrt(2.0), 0.5, 1e-7)), 12.0, Vec3::Zero());
  spec.angular_velocity = w;
  return spec;
}

struct Spin {
  Vec3 momentum;
  Real energy;
};

TEST(BodyMotion, TorqueFreeSpinHoldsAngularMomentumEnergyAndAxis) {
  World world(config(0.0));
  const BodyId id = *world.addBody(inertia123(Vec3(0.01, 0.01, 2.0)));
  const std::size_t i = *world.bodies().find(id);
  EXPECT_NEAR(world.bodies().principalInertia(i).x(), 1.0, 1e-9);
  EXPECT_NEAR(world.bodies().principalInertia(i).y(), 2.0, 1e-9);
  EXPECT_NEAR(world.bodies().principalInertia(i).z(), 3.0, 1e-9);
  const Vec3 l0 = world.angularMomentum();
  const Real e0 = world.kineticEnergy();
  Real worst_l = 0.0;
  Real worst_e = 0.0;
  Real worst_axis = 0.0;
  for (int step = 0; step < 20 * 60; ++step) {
    world.step();
    const Vec3 l = world.angularMomentum();
    worst_l = std::max(worst_l, std::abs(l.norm() / l0.norm() - 1.0));
    worst_e = std::max(worst_e, std::abs(world.kineticEnergy() / e0 - 1.0));
    const Vec3 spin_axis = world.bodies().orientation(i) * Vec3::UnitZ();
    worst_axis = std::max(worst_axis, angleBetween(spin_axis, l0));
  }
  std::printf("[ spin ] 20 s: |L| %.2e, energy %.2e, axis %.3f deg\n", worst_l, worst_e,
              worst_axis * 180.0 / M_PI);
  EXPECT_LT(worst_l, 1e-6);
  EXPECT_LT(worst_e, 1e-3);
  EXPECT_LT(worst_axis, M_PI / 180.0);
}

// w_y in the body frame over 20 s: its sign changes (the flips) and |L| and energy.
struct FlipRun {
  int sign_changes = 0;
  Real worst_l = 0.0;       // |L| relative
  Real worst_turn_l = 0.0;  // |L - L0| / |L0|: the vector, not only its length
  Real worst_e = 0.0;
};

FlipRun intermediateAxis(const bool gyroscopic) {
  World world(config(0.0));
  BodySettings settings;
  settings.gyroscopic = gyroscopic;
  EXPECT_TRUE(world.setBodySettings(settings));
  const BodyId id = *world.addBody(inertia123(Vec3(0.01, 2.0, 0.01)));
  const std::size_t i = *world.bodies().find(id);
  const Vec3 l0 = world.angularMomentum();
  const Real e0 = world.kineticEnergy();
  FlipRun run;
  Real previous = 2.0;
  for (int step = 0; step < 20 * 60; ++step) {
    world.step();
    const Vec3 w_body =
        world.bodies().orientation(i).conjugate() * world.bodies().angularVelocity(i);
    if ((w_body.y() > 0.0) != (previous > 0.0)) ++run.sign_changes;
    previous = w_body.y();
    run.worst_l = std::max(run.worst_l, std::abs(world.angularMomentum().norm() / l0.norm() - 1.0));
    run.worst_turn_l =
        std::max(run.worst_turn_l, (world.angularMomentum() - l0).norm() / l0.norm());
    run.worst_e = std::max(run.worst_e, std::abs(world.kineticEnergy() / e0 - 1.0));
  }
  return run;
}

TEST(BodyMotion, IntermediateAxisFlipsAndFlipsBack) {
  // The growth rate 2 sqrt((I2 - I1)(I3 - I2) / (I1 I3)) = 0.577 W: from 0.01 rad/s the first flip
  // comes after about 3 s, then one every few seconds.
  const FlipRun run = intermediateAxis(true);
  std::printf("[ flip ] %d sign changes of w_y in 20 s, |L| %.2e, L turned %.2e, energy %.2e\n",
              run.sign_changes, run.worst_l, run.worst_turn_l, run.worst_e);
  EXPECT_GE(run.sign_changes, 2);  // over and back
  EXPECT_LT(run.worst_l, 1e-6);
  // Its direction in the world drifts by O(h) (body_motion.h).
  EXPECT_LT(run.worst_turn_l, 1e-2);
  EXPECT_LT(run.worst_e, 1e-3);
}

TEST(BodyMotion, WithoutTheGyroscopicTermTheIntermediateAxisNeverFlips) {
  const FlipRun run = intermediateAxis(false);
  EXPECT_EQ(run.sign_changes, 0);
}

TEST(BodyMotion, FreeFallWithSpinFollowsTheClosedForm) {
  World world(config());
  const Vec3 w(0.3, -0.2, 5.0);
  BodySpec spec = body(box(Vec3::Constant(0.5)), 2.0, Vec3(0.0, 0.0, 100.0));
  spec.angular_velocity = w;  // a cube: every axis principal, no gyroscopic torque
  const BodyId id = *world.addBody(spec);
  const std::size_t i = *world.bodies().find(id);
  const Real h = world.config().dt / world.bodySettings().substeps;
  for (int step = 1; step <= 120; ++step) {
    world.step();
    const Real t = step * world.config().dt;
    const Real z = 100.0 - 0.5 * kG * t * t;
    // Semi-implicit Euler falls h t g / 2 further than the parabola.
    EXPECT_LE(std::abs(world.bodies().position(i).z() - z), 0.5 * kG * h * t * (1.0 + 1e-9));
    const Quat exact(Eigen::AngleAxisd(w.norm() * t, w.normalized()));
    EXPECT_LT(world.bodies().orientation(i).angularDistance(exact), 1e-9) << "t " << t;
  }
}

TEST(BodyMotion, ExponentialMapAgainstTheSeedsFirstOrderUpdate) {
  // One step of each from the same state: they agree to O(h^2); over a second the first-order
  // update drifts from the closed form while the exponential map does not.
  const Vec3 w(0.0, 0.0, 4.0);
  Quat exp_map = Quat::Identity();
  Quat first_order = Quat::Identity();
  const Real h = 1.0 / 60.0;
  const Quat one = rotationOver(w, h);
  const Quat reference = firstOrderRotation(Quat::Identity(), w, h);
  EXPECT_LT(one.angularDistance(reference), w.norm() * w.norm() * h * h);
  for (int i = 0; i < 60; ++i) {
    exp_map = (rotationOver(w, h) * exp_map).normalized();
    first_order = firstOrderRotation(first_order, w, h);
  }
  const Quat exact(Eigen::AngleAxisd(4.0, Vec3::UnitZ()));
  EXPECT_LT(exp_map.angularDistance(exact), 1e-12);
  EXPECT_GT(first_order.angularDistance(exact), 1e-4);
}

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
