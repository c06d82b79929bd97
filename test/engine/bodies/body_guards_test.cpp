// Guards and the state hash for bodies (issue 14): a body running away is a divergence that
// names it, under the same policies as particles (continue, pause, reset to the snapshot); the
// state hash covers the bodies' sleep and the impulses every joint kind carries.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "body_scenes.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

using namespace test_bodies;

// A ball falling freely from 100 m, the runaway speed lowered to 5 m/s: semi-implicit Euler
// gives v = g n dt after n steps exactly (no drag, no contact), so the speed first exceeds 5 m/s
// in step n = ceil(5 / (g dt)) = ceil(30.58) = 31.
constexpr int kRunawayStep = 31;

struct Runaway {
  World world;
  BodyId ball;
};

Runaway fallingBall(const DivergencePolicy policy) {
  WorldConfig c = config();
  c.divergence_policy = policy;
  Runaway r{World(c), BodyId{}};
  BodySettings settings;
  settings.runaway_speed = 5.0;
  settings.sleep = false;
  EXPECT_TRUE(r.world.setBodySettings(settings));
  r.ball = *r.world.addBody(body(sphere(0.1), 1.0, Vec3(0.0, 0.0, 100.0)));
  return r;
}

Real ballHeight(const Runaway& r) {
  return r.world.bodies().position(*r.world.bodies().find(r.ball)).z();
}

TEST(BodyGuards, ARunawayBodyIsADivergenceThatNamesIt) {
  EXPECT_EQ(BodySettings{}.runaway_speed, 1e4);
  ASSERT_EQ(static_cast<int>(std::ceil(5.0 / (kG / 60.0))), kRunawayStep);
  Runaway r = fallingBall(DivergencePolicy::kContinue);
  int fired = -1;
  for (int step = 1; step <= 60 && fired < 0; ++step) {
    r.world.step();
    if (r.world.divergenceCount() > 0) fired = step;
  }
  ASSERT_TRUE(r.world.lastDivergence().has_value());
  const DivergenceEvent& event = *r.world.lastDivergence();
  std::printf("[ runaway ] fired in step %d (expected %d): step %llu, t %.4f s, body %s, \"%s\"\n",
              fired, kRunawayStep, static_cast<unsigned long long>(event.step), event.time,
              event.body.str().c_str(), event.what.c_str());
  EXPECT_EQ(fired, kRunawayStep);
  EXPECT_EQ(event.body, r.ball);
  EXPECT_FALSE(event.particle.valid());
  EXPECT_NE(event.what.find("runaway"), std::string::npos) << event.what;
  // Like a particle's divergence (World.DivergenceIsDetectedInTheStepAndNamesTheParticle): the
  // step that produced it, and the time it ended at.
  EXPECT_EQ(event.step, static_cast<std::uint64_t>(kRunawayStep));
  EXPECT_NEAR(event.time, kRunawayStep / 60.0, 1e-12);
  // kContinue: the world steps on, reporting every step.
  r.world.step();
  EXPECT_EQ(r.world.divergenceCount(), 2u);
  EXPECT_FALSE(r.world.paused());
}

TEST(BodyGuards, ARunawayBodyPausesTheWorldUnderPause) {
  Runaway r = fallingBall(DivergencePolicy::kPause);
  for (int step = 0; step < 60; ++step) r.world.step();
  EXPECT_TRUE(r.world.paused());
  EXPECT_EQ(r.world.divergenceCount(), 1u);
  EXPECT_EQ(r.world.stepCount(), static_cast<std::uint64_t>(kRunawayStep));
  EXPECT_EQ(r.world.lastDivergence()->body, r.ball);
  // Paused: step() and advance() change nothing until resume().
  const std::uint64_t hash = r.world.stateHash();
  r.world.step();
  EXPECT_EQ(r.world.advance(0.1), 0);
  EXPECT_EQ(r.world.stateHash(), hash);
  r.world.resume();
  r.world.step();
  EXPECT_EQ(r.world.stepCount(), static_cast<std::uint64_t>(kRunawayStep + 1));
}

TEST(BodyGuards, ARunawayBodyResetsTheWorldToItsSnapshotUnderReset) {
  Runaway r = fallingBall(DivergencePolicy::kReset);
  for (int step = 0; step < 10; ++step) r.world.step();
  r.world.setResetSnapshot();
  const std::uint64_t snapshot_hash = r.world.stateHash();
  const Real snapshot_height = ballHeight(r);
  // Steps 11 to 31: the 31st runs away and brings back the world of step 10.
  for (int step = 10; step < kRunawayStep; ++step) r.world.step();
  std::printf("[ runaway ] reset: step count %llu, height %.6f m (snapshot %.6f m)\n",
              static_cast<unsigned long long>(r.world.stepCount()), ballHeight(r), snapshot_height);
  EXPECT_EQ(r.world.divergenceCount(), 1u);
  EXPECT_FALSE(r.world.paused());
  EXPECT_EQ(r.world.stepCount(), 10u);
  EXPECT_EQ(ballHeight(r), snapshot_height);
  EXPECT_EQ(r.world.stateHash(), snapshot_hash);
  ASSERT_TRUE(r.world.lastDivergence().has_value());
  EXPECT_EQ(r.world.lastDivergence()->body, r.ball);
  // Without a snapshot, reset pauses.
  Runaway bare = fallingBall(DivergencePolicy::kReset);
  for (int step = 0; step < 60; ++step) bare.world.step();
  EXPECT_TRUE(bare.world.paused());
  EXPECT_EQ(bare.world.stepCount(), static_cast<std::uint64_t>(kRunawayStep));
}

// --- the state hash ---

// The world's joints, to change one stored impulse and nothing else (the hash's contract is
// about state, whatever changed it; World itself only changes them by stepping).
Joints& jointsOf(World& world) { return const_cast<Joints&>(world.joints()); }

// A scene with one joint of every kind, stepped until each carries impulses: a box hanging from
// a ball joint, a rod on a hinge at its limit with its motor on, two boxes welded by a fixed
// joint hanging from a cable (a distance joint).
World jointScene() {
  World world(config());
  BodySettings settings;
  settings.sleep = false;
  EXPECT_TRUE(world.setBodySettings(settings));
  const BodyId hanging = *world.addBody(body(box(Vec3::Constant(0.1)), 1.0, Vec3(0, 0, -1.0)));
  EXPECT_TRUE(world.addJoint(
      BallJoint{JointEnd::inWorld(Vec3::Zero()), JointEnd::onBody(hanging, Vec3(0, 0, 1.0))}));
  const BodyId rod = *world.addBody(body(box(Vec3(0.5, 0.01, 0.01)), 1.0, Vec3(3.5, 0, 0)));
  HingeJoint hinge;
  hinge.a = JointEnd::inWorld(Vec3(3.0, 0.0, 0.0));
  hinge.b = JointEnd::onBody(rod, Vec3(-0.5, 0.0, 0.0));
  hinge.axis = Vec3::UnitY();
  hinge.limit = true;
  hinge.lower = -0.1;
  hinge.upper = 0.1;
  hinge.motor = true;
  hinge.motor_speed = 0.5;
  hinge.max_motor_torque = 0.5;
  EXPECT_TRUE(world.addJoint(hinge));
  const BodyId top = *world.addBody(body(box(Vec3::Constant(0.1)), 1.0, Vec3(6, 0, -1.0)));
  const BodyId bottom = *world.addBody(body(box(Vec3::Constant(0.1)), 1.0, Vec3(6, 0, -1.3)));
  EXPECT_TRUE(world.addJoint(
      FixedJoint{JointEnd::onBody(top), JointEnd::onBody(bottom, Vec3(0.0, 0.0, 0.3))}));
  EXPECT_TRUE(world.addJoint(DistanceJoint::cable(JointEnd::inWorld(Vec3(6, 0, 0)),
                                                  JointEnd::onBody(top, Vec3(0, 0, 0.1)), 0.9)));
  for (int step = 0; step < 30; ++step) world.step();
  return world;
}

TEST(BodyStateHash, CoversEveryJointsImpulses) {
  const World world = jointScene();
  const std::uint64_t hash = world.stateHash();
  EXPECT_EQ(World(world).stateHash(), hash);
  // Each stored impulse, nudged by one part in 1e12 (or set, where it is zero) in a copy: the
  // copies differ from the original only there, and their hashes must differ.
  const auto nudge = [](Real& value) { value = value != 0.0 ? value * (1.0 + 1e-12) : 1e-12; };
  const std::vector<std::pair<const char*, std::function<void(Joints&)>>> changes = {
      {"ball linear", [&](Joints& j) { nudge(j.of<BallJoint>()[0].linear_impulse.z()); }},
      {"hinge linear", [&](Joints& j) { nudge(j.of<HingeJoint>()[0].linear_impulse.z()); }},
      {"hinge angular", [&](Joints& j) { nudge(j.of<HingeJoint>()[0].angular_impulse.x()); }},
      {"hinge lower", [&](Joints& j) { nudge(j.of<HingeJoint>()[0].lower_impulse); }},
      {"hinge upper", [&](Joints& j) { nudge(j.of<HingeJoint>()[0].upper_impulse); }},
      {"hinge motor", [&](Joints& j) { nudge(j.of<HingeJoint>()[0].motor_impulse); }},
      {"fixed linear", [&](Joints& j) { nudge(j.of<FixedJoint>()[0].linear_impulse.z()); }},
      {"fixed angular", [&](Joints& j) { nudge(j.of<FixedJoint>()[0].angular_impulse.y()); }},
      {"distance lower", [&](Joints& j) { nudge(j.of<DistanceJoint>()[0].lower_impulse); }},
      {"distance upper", [&](Joints& j) { nudge(j.of<DistanceJoint>()[0].upper_impulse); }},
  };
  for (const auto& [name, change] : changes) {
    World copy = world;
    change(jointsOf(copy));
    EXPECT_NE(copy.stateHash(), hash) << name;
  }
}

TEST(BodyStateHash, AMotorDrivenAtAnotherSpeedChangesTheHashFromTheNextStep) {
  // A wheel (I_z = 1/3 kg m^2) on a motorised hinge without gravity, at its 4 rad/s after 2 s.
  // Two copies, the motor set to 4.5 rad/s in one and left at 4 in the other (within its torque,
  // 1 N m: 3 rad/s^2, so the faster one gains 3 dt = 0.05 rad/s in the next step). The hinge's
  // hash (JointKind<HingeJoint>::addToHash) covers its impulses, not its motor's settings (as a
  // spring's stiffness or a body's mass are not hashed), so right after the call the hashes
  // still agree; a step later the motor's impulse and the wheel's velocity differ, and so do
  // the hashes.
  World world(config(0.0));
  const BodyId wheel = *world.addBody(body(box(Vec3(0.5, 0.5, 0.1)), 2.0, Vec3::Zero()));
  HingeJoint hinge;
  hinge.a = JointEnd::inWorld(Vec3::Zero());
  hinge.b = JointEnd::onBody(wheel);
  hinge.axis = Vec3::UnitZ();
  hinge.motor = true;
  hinge.motor_speed = 4.0;
  hinge.max_motor_torque = 1.0;
  const JointId id = *world.addJoint(hinge);
  for (int step = 0; step < 120; ++step) world.step();
  World faster = world;
  World same = world;
  ASSERT_TRUE(faster.setHingeMotor(id, true, 4.5, 1.0));
  ASSERT_TRUE(same.setHingeMotor(id, true, 4.0, 1.0));
  faster.step();
  same.step();
  const std::size_t i = *world.bodies().find(wheel);
  std::printf("[ hash ] motor at 4.5 against 4 rad/s: w %.6f against %.6f rad/s a step later\n",
              faster.bodies().angularVelocity(i).z(), same.bodies().angularVelocity(i).z());
  EXPECT_NEAR(faster.bodies().angularVelocity(i).z() - same.bodies().angularVelocity(i).z(),
              3.0 / 60.0, 1e-6);
  EXPECT_NE(faster.stateHash(), same.stateHash());
}

TEST(BodyStateHash, CoversTheSleepTimer) {
  // Two copies of a cube resting on the ground, awake and slow for 10 steps; wakeBody on the
  // awake cube of one changes only its slow time (back to zero): the hashes differ. Stepped
  // on, the woken copy sleeps 10 steps later than the other.
  World world(config());
  addGround(world);
  const BodyId id = *world.addBody(body(box(Vec3::Constant(0.5)), 1.0, Vec3(0.0, 0.0, 0.5)));
  for (int step = 0; step < 10; ++step) world.step();
  const std::size_t i = *world.bodies().find(id);
  ASSERT_TRUE(world.bodies().awake(i));
  ASSERT_GT(world.bodies().sleepTime(i), 0.0);
  World woken = world;
  ASSERT_TRUE(woken.wakeBody(id));
  EXPECT_EQ(woken.bodies().sleepTime(i), 0.0);
  EXPECT_EQ(woken.bodies().position(i), world.bodies().position(i));
  EXPECT_EQ(woken.bodies().linearVelocity(i), world.bodies().linearVelocity(i));
  EXPECT_EQ(woken.bodies().awake(i), world.bodies().awake(i));
  EXPECT_NE(woken.stateHash(), world.stateHash());
  int world_slept = -1;
  int woken_slept = -1;
  for (int step = 1; step <= 60; ++step) {
    world.step();
    woken.step();
    if (world_slept < 0 && !world.bodies().awake(i)) world_slept = step;
    if (woken_slept < 0 && !woken.bodies().awake(i)) woken_slept = step;
  }
  std::printf("[ hash ] sleep timer reset: asleep %d steps later (%d against %d)\n",
              woken_slept - world_slept, woken_slept, world_slept);
  EXPECT_EQ(woken_slept - world_slept, 10);
}

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
