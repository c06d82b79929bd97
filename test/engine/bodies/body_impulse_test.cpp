// Impulses and two-way coupling (issue 14's acceptance test 12), forces and requests on bodies,
// refusals that change nothing.
#include <gtest/gtest.h>

#include <cmath>

#include "body_scenes.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

using namespace test_bodies;

TEST(BodyImpulse, AnImpulseAtAPointGivesTheExactKick) {
  World world(config(0.0));
  const BodyId id = *world.addBody(body(box(Vec3::Constant(0.5)), 1.0, Vec3(1.0, 2.0, 3.0)));
  const std::size_t i = *world.bodies().find(id);
  // J = (0, 1, 0) N s at r = (0.5, 0, 0) on a 1 kg unit cube (I = m / 6): dv = 1 m/s,
  // dw = 6 (r x J) = (0, 0, 3) rad/s.
  ASSERT_TRUE(world.applyBodyImpulse(id, Vec3(0.0, 1.0, 0.0), Vec3(1.5, 2.0, 3.0)));
  EXPECT_LT((world.bodies().linearVelocity(i) - Vec3(0.0, 1.0, 0.0)).norm(), 1e-9);
  EXPECT_LT((world.bodies().angularVelocity(i) - Vec3(0.0, 0.0, 3.0)).norm(), 1e-9);
  // And an angular impulse L: dw = I^-1 L.
  ASSERT_TRUE(world.applyBodyImpulse(id, Vec3::Zero(), Vec3::Zero(), Vec3(1.0 / 6.0, 0.0, 0.0)));
  EXPECT_LT((world.bodies().angularVelocity(i) - Vec3(1.0, 0.0, 3.0)).norm(), 1e-9);
}

TEST(BodyImpulse, AForceAtAPointForOneStepGivesFDtAndItsTorque) {
  World world(config(0.0));
  const BodyId id = *world.addBody(body(box(Vec3::Constant(0.5)), 2.0, Vec3::Zero()));
  const std::size_t i = *world.bodies().find(id);
  ASSERT_TRUE(world.addBodyForce(id, Vec3(0.0, 6.0, 0.0), Vec3(0.5, 0.0, 0.0)));
  world.step();
  const Real dt = world.config().dt;
  // dv = F dt / m; dw = I^-1 (r x F) dt with I = m / 6.
  EXPECT_LT((world.bodies().linearVelocity(i) - Vec3(0.0, 3.0 * dt, 0.0)).norm(), 1e-12);
  EXPECT_NEAR(world.bodies().angularVelocity(i).z(), 3.0 * 3.0 * dt, 1e-12);
  world.step();  // held for one step only
  EXPECT_LT((world.bodies().linearVelocity(i) - Vec3(0.0, 3.0 * dt, 0.0)).norm(), 1e-12);
}

TEST(BodyImpulse, AParticleDroppedOnABodysBoxMovesIt) {
  // Two-way: the particle pushes the body down, the body stops the particle; without gravity
  // and nothing else, momentum is conserved through the impact.
  World world(config(0.0));
  const BodyId id = *world.addBody(body(box(Vec3(1.0, 1.0, 0.25)), 2.0, Vec3::Zero()));
  const std::size_t i = *world.bodies().find(id);
  ParticleSpec spec;
  spec.position = Vec3(0.1, -0.2, 1.0);
  spec.velocity = Vec3(0.0, 0.0, -3.0);
  spec.inverse_mass = 1.0 / 0.5;
  spec.radius = 0.05;
  const ParticleId p = *world.addParticle(spec);
  const Vec3 p0 = world.linearMomentum();
  Real worst = 0.0;
  for (int step = 0; step < 60; ++step) {
    world.step();
    worst = std::max(worst, (world.linearMomentum() - p0).norm());
  }
  const Vec3 v_body = world.bodies().linearVelocity(i);
  const Vec3 v_particle = world.particles().velocities().col(*world.particles().find(p));
  std::printf("[ two-way ] body %.4f m/s down, particle %.4f m/s, momentum error %.2e\n",
              -v_body.z(), v_particle.z(), worst);
  EXPECT_LT(v_body.z(), -0.1);  // the particle pushed the body
  EXPECT_GT(v_particle.z(), -3.0 + 0.1);
  EXPECT_LT(worst, 1e-9);
}

TEST(BodyImpulse, AParticleLandingOnASpinningBodysAxisLeavesItsSpin) {
  // On the axis the body's surface does not move under the particle: no friction, and a particle
  // cannot turn, so its contact has no twist (BodySettings::min_twist_lever) to take the spin.
  World world(config(0.0));
  BodySpec spec = body(box(Vec3(1.0, 1.0, 0.25)), 2.0, Vec3::Zero());
  spec.angular_velocity = Vec3(0.0, 0.0, 1.0);
  const std::size_t i = *world.bodies().find(*world.addBody(spec));
  ParticleSpec particle;
  particle.position = Vec3(0.0, 0.0, 1.0);
  particle.velocity = Vec3(0.0, 0.0, -3.0);
  particle.inverse_mass = 1.0 / 0.5;
  particle.radius = 0.05;
  const ParticleId p = *world.addParticle(particle);
  ASSERT_TRUE(world.setParticleMaterial(p, Material{0.0, 0.5}));
  for (int step = 0; step < 60; ++step) world.step();
  const Vec3 w = world.bodies().angularVelocity(i);
  std::printf("[ axis ] body w (%.3e %.3e %.15f) rad/s, body %.4f m/s down\n", w.x(), w.y(), w.z(),
              -world.bodies().linearVelocity(i).z());
  EXPECT_LT(world.bodies().linearVelocity(i).z(), -0.1);  // the particle hit it
  EXPECT_GT(world.particles().velocities().col(*world.particles().find(p)).z(), -3.0 + 0.1);
  EXPECT_NEAR(w.z(), 1.0, 1e-12);
  EXPECT_LT(w.head<2>().norm(), 1e-12);
}

TEST(BodyImpulse, RefusedRequestsChangeNothing) {
  World world(config());
  const BodyId id = *world.addBody(body(box(Vec3::Constant(0.5)), 1.0, Vec3::Zero()));
  world.step();
  const std::uint64_t before = world.stateHash();
  const Real nan = std::nan("");
  EXPECT_FALSE(world.applyBodyImpulse(id, Vec3(nan, 0, 0), Vec3::Zero()));
  EXPECT_FALSE(world.addBodyForce(id, Vec3::Zero(), Vec3(0, nan, 0)));
  EXPECT_FALSE(world.setBodyVelocity(id, Vec3::Zero(), Vec3(0, 0, nan)));
  Transform bad;
  bad.rotation = Quat(2.0, 0.0, 0.0, 0.0);  // not unit
  EXPECT_FALSE(world.setBodyPose(id, bad));
  EXPECT_FALSE(world.applyBodyImpulse(BodyId{}, Vec3::UnitX(), Vec3::Zero()));
  BodySpec empty;
  EXPECT_FALSE(world.addBody(empty));  // no shape
  BodySpec negative = body(box(Vec3(0.5, -1.0, 0.5)), 1.0, Vec3::Zero());
  EXPECT_FALSE(world.addBody(negative));
  BodySpec massless = body(box(Vec3::Constant(0.5)), -1.0, Vec3::Zero());
  EXPECT_FALSE(world.addBody(massless));
  BodySpec zero_q = body(box(Vec3::Constant(0.5)), 1.0, Vec3::Zero());
  zero_q.pose.rotation = Quat(0.0, 0.0, 0.0, 0.0);
  EXPECT_FALSE(world.addBody(zero_q));
  EXPECT_FALSE(world.addJoint(BallJoint{JointEnd::onBody(id), JointEnd::onBody(id)}));
  EXPECT_EQ(world.stateHash(), before);
}

TEST(BodyImpulse, RemovingABodyRemovesItsJointsAndWakesWhatRestedOnIt) {
  World world(config());
  addGround(world);
  const BodyId lower = *world.addBody(body(box(Vec3::Constant(0.5)), 1.0, Vec3(0, 0, 0.5)));
  const BodyId upper = *world.addBody(body(box(Vec3::Constant(0.5)), 1.0, Vec3(0, 0, 1.5)));
  ASSERT_TRUE(world.addJoint(
      BallJoint{JointEnd::onBody(upper, Vec3(0, 0, 0.5)), JointEnd::inWorld(Vec3(0, 0, 2.0))}));
  for (int step = 0; step < 120; ++step) world.step();
  EXPECT_EQ(world.joints().size(), 1u);
  ASSERT_TRUE(world.removeBody(upper));
  EXPECT_EQ(world.joints().size(), 0u);
  EXPECT_FALSE(world.bodies().contains(upper));
  EXPECT_TRUE(world.bodies().awake(*world.bodies().find(lower)));
  for (int step = 0; step < 60; ++step) world.step();
  EXPECT_EQ(world.divergenceCount(), 0u);
}

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
