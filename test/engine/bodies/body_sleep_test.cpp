// Sleeping by islands (issue 14): an island sleeps once every body in it has been slower than
// BodySettings::sleep_speed for time_to_sleep (0.5 s); the bodies of an island (joined by
// contacts or joints) sleep and wake together; every request that touches a body wakes its
// island, and a particle hitting a sleeping body wakes it, while other islands sleep on.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "body_scenes.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

using namespace test_bodies;

bool asleep(const World& world, const BodyId id) {
  return !world.bodies().awake(*world.bodies().find(id));
}

// How the sleep stage measures a body's speed: the fastest any point of it can move.
Real pointSpeed(const World& world, const BodyId id) {
  const std::size_t i = *world.bodies().find(id);
  return world.bodies().linearVelocity(i).norm() +
         world.bodies().angularVelocity(i).norm() * world.bodies().reach(i);
}

// Steps of dt it takes to have been slow for time_to_sleep: each slow step adds dt to the body's
// slow time, and the island sleeps in the step where that reaches time_to_sleep to the nearest
// step (thirty additions of 1/60 give 0.49999999999999994, not 0.5, in doubles): 30 steps for
// 0.5 s at 60 Hz.
int stepsToSleep(const World& world) {
  Real slow = 0.0;
  int steps = 0;
  while (slow < world.bodySettings().time_to_sleep - 0.5 * world.config().dt) {
    slow += world.config().dt;
    ++steps;
  }
  return steps;
}

TEST(BodySleep, ABodySleepsAfterHalfASecondBelowTheSleepSpeed) {
  // No gravity, no contact: a box drifting at 0.03 m/s (below sleep_speed, 0.05 m/s) is slow
  // from its first step and sleeps once it has been slow for 0.5 s (in step 30, stepsToSleep),
  // its velocity zeroed; one drifting at 0.06 m/s never sleeps.
  World world(config(0.0));
  EXPECT_EQ(world.bodySettings().time_to_sleep, 0.5);
  EXPECT_EQ(world.bodySettings().sleep_speed, 0.05);
  BodySpec slow = body(box(Vec3::Constant(0.5)), 1.0, Vec3::Zero());
  slow.linear_velocity = Vec3(0.03, 0.0, 0.0);
  BodySpec fast = body(box(Vec3::Constant(0.5)), 1.0, Vec3(0.0, 5.0, 0.0));
  fast.linear_velocity = Vec3(0.06, 0.0, 0.0);
  const BodyId slow_id = *world.addBody(slow);
  const BodyId fast_id = *world.addBody(fast);
  const int expected = stepsToSleep(world);
  ASSERT_NEAR(expected * world.config().dt, 0.5, world.config().dt);
  int slept_at = -1;
  Vec3 where_it_slept = Vec3::Zero();
  for (int step = 1; step <= 120; ++step) {
    world.step();
    if (slept_at < 0 && asleep(world, slow_id)) {
      slept_at = step;
      where_it_slept = world.bodies().position(*world.bodies().find(slow_id));
    }
  }
  std::printf("[ sleep ] drifting at 0.03 m/s: asleep after step %d (%.4f s; expected %d)\n",
              slept_at, slept_at / 60.0, expected);
  EXPECT_EQ(slept_at, expected);
  const std::size_t i = *world.bodies().find(slow_id);
  EXPECT_TRUE(world.bodies().linearVelocity(i).isZero(0.0));
  EXPECT_EQ(world.bodies().position(i), where_it_slept);  // not stepped while asleep
  EXPECT_FALSE(asleep(world, fast_id));
}

TEST(BodySleep, ASlidingBoxSleepsHalfASecondAfterItSlowedDown) {
  // A cube sent at 0.5 m/s along the ground (mu 0.5) slows at mu g = 4.905 m/s^2: below
  // sleep_speed after (0.5 - 0.05) / (mu g) = 0.0917 s, so step 5 (0.083 s) is its last fast one.
  // It sleeps 0.5 s of slow steps (stepsToSleep) after that.
  World world(config());
  addGround(world);
  BodySpec spec = body(box(Vec3::Constant(0.5)), 1.0, Vec3(0.0, 0.0, 0.5));
  spec.linear_velocity = Vec3(0.5, 0.0, 0.0);
  const BodyId id = *world.addBody(spec);
  int last_fast = 0;
  int slept_at = -1;
  for (int step = 1; step <= 120 && slept_at < 0; ++step) {
    world.step();
    if (asleep(world, id)) {
      slept_at = step;
    } else if (pointSpeed(world, id) >= world.bodySettings().sleep_speed) {
      last_fast = step;
    }
  }
  std::printf("[ sleep ] sliding box: last fast in step %d (%.4f s), asleep after step %d\n",
              last_fast, last_fast / 60.0, slept_at);
  EXPECT_EQ(last_fast, static_cast<int>(std::floor((0.5 - 0.05) / (0.5 * kG) * 60.0)));
  EXPECT_EQ(slept_at, last_fast + stepsToSleep(world));
}

TEST(BodySleep, AnIslandStaysAwakeWhileOneOfItsBodiesMoves) {
  // Without gravity, box a rests; box b, 1 m from it, moves away at 0.1 m/s. Tied to a by a
  // slack 3 m cable (taut only after 20 s) it is in a's island, and a never sleeps in 2 s; the
  // same pair without the cable: a sleeps after 0.5 s.
  for (const bool tied : {true, false}) {
    World world(config(0.0));
    const BodyId a = *world.addBody(body(box(Vec3::Constant(0.25)), 1.0, Vec3::Zero()));
    BodySpec moving = body(box(Vec3::Constant(0.25)), 1.0, Vec3(1.0, 0.0, 0.0));
    moving.linear_velocity = Vec3(0.1, 0.0, 0.0);
    const BodyId b = *world.addBody(moving);
    if (tied) {
      ASSERT_TRUE(
          world.addJoint(DistanceJoint::cable(JointEnd::onBody(a), JointEnd::onBody(b), 3.0)));
    }
    int slept_at = -1;
    for (int step = 1; step <= 120 && slept_at < 0; ++step) {
      world.step();
      if (asleep(world, a)) slept_at = step;
    }
    std::printf("[ sleep ] resting box %s a moving one: asleep after step %d\n",
                tied ? "tied to" : "apart from", slept_at);
    EXPECT_EQ(slept_at, tied ? -1 : stepsToSleep(world));
    EXPECT_FALSE(asleep(world, b));
  }
}

TEST(BodySleep, TwoBodiesJoinedByAJointSleepAndWakeTogether) {
  // Without gravity two boxes joined by a ball joint, both at rest, and a third alone: all are
  // slow from the first step and sleep after 0.5 s of it (stepsToSleep), the joined two in the
  // same step. Waking one of the joined two wakes the other (its island), not the third.
  World world(config(0.0));
  const BodyId a = *world.addBody(body(box(Vec3::Constant(0.25)), 1.0, Vec3::Zero()));
  const BodyId b = *world.addBody(body(box(Vec3::Constant(0.25)), 1.0, Vec3(1.0, 0.0, 0.0)));
  const BodyId alone = *world.addBody(body(box(Vec3::Constant(0.25)), 1.0, Vec3(5.0, 0.0, 0.0)));
  ASSERT_TRUE(world.addJoint(
      BallJoint{JointEnd::onBody(a, Vec3(0.5, 0.0, 0.0)), JointEnd::onBody(b, Vec3(-0.5, 0, 0))}));
  int a_slept = -1;
  int b_slept = -1;
  for (int step = 1; step <= 60; ++step) {
    world.step();
    if (a_slept < 0 && asleep(world, a)) a_slept = step;
    if (b_slept < 0 && asleep(world, b)) b_slept = step;
  }
  std::printf("[ sleep ] jointed pair asleep after steps %d and %d\n", a_slept, b_slept);
  EXPECT_EQ(a_slept, stepsToSleep(world));
  EXPECT_EQ(b_slept, a_slept);
  ASSERT_TRUE(asleep(world, alone));
  ASSERT_TRUE(world.wakeBody(b));
  EXPECT_FALSE(asleep(world, a));
  EXPECT_FALSE(asleep(world, b));
  EXPECT_TRUE(asleep(world, alone));
}

// Two unit cubes stacked on the ground (an island by their contact), a third apart (an island of
// its own) dropped from 5 cm so that it settles later, and a hinge about y holding the top of the
// upper cube to the world (at rest it pulls nothing). Stepped until all three sleep.
struct SleepingScene {
  World world{config()};
  BodyId lower;
  BodyId upper;
  BodyId apart;
  JointId hinge = 0;
  int lower_slept = -1;
  int upper_slept = -1;
  int apart_slept = -1;
};

SleepingScene sleepingScene() {
  SleepingScene s;
  addGround(s.world);
  s.lower = *s.world.addBody(body(box(Vec3::Constant(0.5)), 1.0, Vec3(0.0, 0.0, 0.5)));
  s.upper = *s.world.addBody(body(box(Vec3::Constant(0.5)), 1.0, Vec3(0.0, 0.0, 1.5)));
  s.apart = *s.world.addBody(body(box(Vec3::Constant(0.5)), 1.0, Vec3(5.0, 0.0, 0.55)));
  HingeJoint hinge;
  hinge.a = JointEnd::inWorld(Vec3(0.0, 0.0, 2.0));
  hinge.b = JointEnd::onBody(s.upper, Vec3(0.0, 0.0, 0.5));
  hinge.axis = Vec3::UnitY();
  s.hinge = *s.world.addJoint(hinge);
  for (int step = 1; step <= 180; ++step) {
    s.world.step();
    if (s.lower_slept < 0 && asleep(s.world, s.lower)) s.lower_slept = step;
    if (s.upper_slept < 0 && asleep(s.world, s.upper)) s.upper_slept = step;
    if (s.apart_slept < 0 && asleep(s.world, s.apart)) s.apart_slept = step;
  }
  return s;
}

TEST(BodySleep, TheIslandCountIsTheSleepStagesGrouping) {
  // On the ground: a stack of two cubes (one island), a cube apart (one), two cubes on a fixed
  // table 3 m apart (two: a fixed body joins none), and two cubes tied by a slack cable (one:
  // a joint joins them though they never touch). Before the first step no contact exists yet,
  // so the stack counts twice; once they rest, 5. All sleep, and the count stays.
  World world(config());
  EXPECT_EQ(world.bodyIslandCount(), 0u);
  addGround(world);
  const Vec3 half = Vec3::Constant(0.5);
  ASSERT_TRUE(world.addBody(body(box(half), 1.0, Vec3(0.0, 0.0, 0.5))));
  ASSERT_TRUE(world.addBody(body(box(half), 1.0, Vec3(0.0, 0.0, 1.5))));
  ASSERT_TRUE(world.addBody(body(box(half), 1.0, Vec3(5.0, 0.0, 0.5))));
  BodySpec table = body(box(Vec3(3.0, 1.0, 0.5)), 1.0, Vec3(0.0, 10.0, 0.5));
  table.type = BodyType::kFixed;
  ASSERT_TRUE(world.addBody(table));
  ASSERT_TRUE(world.addBody(body(box(half), 1.0, Vec3(-1.5, 10.0, 1.5))));
  ASSERT_TRUE(world.addBody(body(box(half), 1.0, Vec3(1.5, 10.0, 1.5))));
  const BodyId left = *world.addBody(body(box(half), 1.0, Vec3(-1.5, -10.0, 0.5)));
  const BodyId right = *world.addBody(body(box(half), 1.0, Vec3(1.5, -10.0, 0.5)));
  ASSERT_TRUE(
      world.addJoint(DistanceJoint::cable(JointEnd::onBody(left), JointEnd::onBody(right), 5.0)));
  EXPECT_EQ(world.bodyIslandCount(), 6u);
  world.step();
  EXPECT_EQ(world.bodyIslandCount(), 5u);
  for (int step = 0; step < 60; ++step) world.step();
  std::size_t sleeping = 0;
  for (std::size_t i = 0; i < world.bodies().size(); ++i) {
    if (world.bodies().dynamic(i) && !world.bodies().awake(i)) ++sleeping;
  }
  EXPECT_EQ(sleeping, 7u);
  EXPECT_EQ(world.bodyIslandCount(), 5u);
}

TEST(BodySleep, AStackSleepsAndWakesAsOneIsland) {
  SleepingScene s = sleepingScene();
  std::printf("[ sleep ] stack asleep after steps %d (lower) and %d (upper), the box apart %d\n",
              s.lower_slept, s.upper_slept, s.apart_slept);
  ASSERT_GT(s.lower_slept, 0);
  EXPECT_EQ(s.lower_slept, s.upper_slept);  // one island: together
  ASSERT_GT(s.apart_slept, 0);
  EXPECT_GT(s.apart_slept, s.lower_slept);  // its own island: on its own time
  // Waking either cube of the stack wakes both, and only them.
  for (const bool wake_lower : {true, false}) {
    SleepingScene copy = s;
    ASSERT_TRUE(copy.world.wakeBody(wake_lower ? copy.lower : copy.upper));
    EXPECT_FALSE(asleep(copy.world, copy.lower));
    EXPECT_FALSE(asleep(copy.world, copy.upper));
    EXPECT_TRUE(asleep(copy.world, copy.apart));
    // Left alone, they sleep again together, 0.5 s later.
    int lower_again = -1;
    int upper_again = -1;
    for (int step = 1; step <= 60; ++step) {
      copy.world.step();
      if (lower_again < 0 && asleep(copy.world, copy.lower)) lower_again = step;
      if (upper_again < 0 && asleep(copy.world, copy.upper)) upper_again = step;
    }
    EXPECT_EQ(lower_again, stepsToSleep(copy.world));
    EXPECT_EQ(upper_again, lower_again);
  }
}

// An island woken by a body landing on it is solved from the step it wakes: its resting
// contacts hold it where it slept, instead of letting it fall for a step (about g dt^2 = 2.7 mm)
// before they act again.
TEST(BodySleep, AStackWokenByABodyLandingOnItHoldsFromThatStep) {
  World world(config());
  addGround(world);
  std::vector<BodyId> stack;
  for (int k = 0; k < 3; ++k) {
    stack.push_back(*world.addBody(body(box(Vec3::Constant(0.5)), 1.0, Vec3(0.0, 0.0, 0.5 + k))));
  }
  for (int step = 0; step < 120 && !asleep(world, stack.back()); ++step) world.step();
  ASSERT_TRUE(asleep(world, stack.front()));
  ASSERT_TRUE(asleep(world, stack.back()));
  std::vector<Real> slept_at;
  for (const BodyId id : stack)
    slept_at.push_back(world.bodies().pose(*world.bodies().find(id)).position.z());
  // A light ball falling onto the top box: it touches in flight, so the stack wakes through it.
  BodySpec ball = body(sphere(0.1), 0.01, Vec3(0.0, 0.0, 3.2));
  ball.linear_velocity = Vec3(0.0, 0.0, -1.0);
  ASSERT_TRUE(world.addBody(ball));
  int woke_at = -1;
  Real worst_drop = 0.0;
  for (int step = 1; step <= 30; ++step) {
    world.step();
    if (woke_at < 0 && !asleep(world, stack.front())) woke_at = step;
    if (woke_at < 0) continue;
    for (std::size_t k = 0; k < stack.size(); ++k) {
      const Real z = world.bodies().pose(*world.bodies().find(stack[k])).position.z();
      worst_drop = std::max(worst_drop, slept_at[k] - z);
    }
  }
  std::printf("[ sleep ] stack woke in step %d, sank at most %.3g m after\n", woke_at, worst_drop);
  ASSERT_GT(woke_at, 0);
  EXPECT_LT(worst_drop, 2e-4);
}

// A fixed body moved by a request (no step moves it, so nothing else would wake what it leaves
// or reaches): a box that slept on it wakes and falls, and a ball it now touches wakes.
TEST(BodySleep, MovingAFixedBodyWakesWhatRestedOnItAndWhatItReaches) {
  World world(config());
  addGround(world);
  BodySpec platform = body(box(Vec3(1.0, 1.0, 0.1)), 1.0, Vec3(0.0, 0.0, 1.0));
  platform.type = BodyType::kFixed;
  const BodyId platform_id = *world.addBody(platform);
  const BodyId on_top = *world.addBody(body(box(Vec3::Constant(0.25)), 1.0, Vec3(0.0, 0.0, 1.35)));
  const BodyId ball = *world.addBody(body(sphere(0.2), 1.0, Vec3(5.0, 0.0, 0.2)));
  for (int step = 0; step < 120 && !(asleep(world, on_top) && asleep(world, ball)); ++step) {
    world.step();
  }
  ASSERT_TRUE(asleep(world, on_top));
  ASSERT_TRUE(asleep(world, ball));
  // Its lower face now 5 mm above the ball.
  ASSERT_TRUE(world.setBodyPose(platform_id, Transform{Vec3(5.0, 0.0, 0.505), Quat::Identity()}));
  EXPECT_FALSE(asleep(world, on_top));
  EXPECT_FALSE(asleep(world, ball));
  for (int step = 0; step < 60; ++step) world.step();
  EXPECT_NEAR(world.bodies().pose(*world.bodies().find(on_top)).position.z(), 0.25, 0.01);
}

// A fixed floor box under separate islands (three cubes apart, each its own island, and a stack
// of two), a cube asleep on the ground beside it, and two balls hanging on ball joints from a fixed
// hub (two islands: a fixed body joins none). Tilting the floor wakes every island on it in one
// request and not the cube beside it; removing the floor does the same; removing the hub wakes
// both that hung from it and nothing else.
TEST(BodySleep, AFixedBodyMovedOrRemovedWakesEveryIslandItHeldAndNoOther) {
  World world(config());
  addGround(world);
  BodySpec floor = body(box(Vec3(4.0, 1.0, 0.1)), 1.0, Vec3(0.0, 0.0, 0.1));
  floor.type = BodyType::kFixed;
  const BodyId floor_id = *world.addBody(floor);
  const Vec3 half = Vec3::Constant(0.5);
  std::vector<BodyId> on_floor;
  for (const Real x : {-3.0, -1.0, 1.0}) {
    on_floor.push_back(*world.addBody(body(box(half), 1.0, Vec3(x, 0.0, 0.7))));
  }
  on_floor.push_back(*world.addBody(body(box(half), 1.0, Vec3(3.0, 0.0, 0.7))));
  on_floor.push_back(*world.addBody(body(box(half), 1.0, Vec3(3.0, 0.0, 1.7))));
  const BodyId beside = *world.addBody(body(box(half), 1.0, Vec3(0.0, 3.0, 0.5)));
  BodySpec hub = body(sphere(0.1), 1.0, Vec3(0.0, -5.0, 3.0));
  hub.type = BodyType::kFixed;
  const BodyId hub_id = *world.addBody(hub);
  std::vector<BodyId> hanging;
  for (const Real x : {-0.5, 0.5}) {
    hanging.push_back(*world.addBody(body(sphere(0.1), 1.0, Vec3(x, -5.0, 2.0))));
    BallJoint joint;
    joint.a = JointEnd::onBody(hub_id, Vec3(x, 0.0, 0.0));
    joint.b = JointEnd::onBody(hanging.back(), Vec3(0.0, 0.0, 1.0));
    ASSERT_TRUE(world.addJoint(joint));
  }
  for (int step = 0; step < 240; ++step) world.step();
  ASSERT_EQ(world.bodyIslandCount(), 7u);  // 3 cubes, the stack, the cube beside, the 2 hanging
  for (const BodyId id : on_floor) ASSERT_TRUE(asleep(world, id));
  ASSERT_TRUE(asleep(world, beside));
  for (const BodyId id : hanging) ASSERT_TRUE(asleep(world, id));

  World tilted = world;
  const Quat tilt(Eigen::AngleAxis<Real>(0.01, Vec3::UnitX()));
  ASSERT_TRUE(tilted.setBodyPose(floor_id, Transform{Vec3(0.0, 0.0, 0.1), tilt}));
  World removed = world;
  ASSERT_TRUE(removed.removeBody(floor_id));
  for (const World* w : {&tilted, &removed}) {
    for (const BodyId id : on_floor) EXPECT_FALSE(asleep(*w, id));
    EXPECT_TRUE(asleep(*w, beside));
    for (const BodyId id : hanging) EXPECT_TRUE(asleep(*w, id));
  }
  World unhung = world;
  ASSERT_TRUE(unhung.removeBody(hub_id));
  for (const BodyId id : hanging) EXPECT_FALSE(asleep(unhung, id));
  for (const BodyId id : on_floor) EXPECT_TRUE(asleep(unhung, id));
  EXPECT_TRUE(asleep(unhung, beside));
}

TEST(BodySleep, NewBodySettingsWakeEveryBodyAndTheSameOnesNone) {
  const SleepingScene s = sleepingScene();
  ASSERT_TRUE(asleep(s.world, s.lower) && asleep(s.world, s.upper) && asleep(s.world, s.apart));
  SleepingScene same = s;
  ASSERT_TRUE(same.world.setBodySettings(s.world.bodySettings()));
  EXPECT_TRUE(asleep(same.world, s.lower) && asleep(same.world, s.upper) &&
              asleep(same.world, s.apart));
  // Any field that differs counts, the first and the last of the struct among them.
  const std::vector<std::function<void(BodySettings&)>> changes = {
      [](BodySettings& b) { b.substeps += 1; },
      [](BodySettings& b) { b.iterations += 1; },
      [](BodySettings& b) { b.guess_loads = !b.guess_loads; },
      [](BodySettings& b) { b.shock_propagation = !b.shock_propagation; },
      [](BodySettings& b) { b.min_twist_lever *= 2.0; },
      [](BodySettings& b) { b.runaway_speed *= 2.0; }};
  for (std::size_t k = 0; k < changes.size(); ++k) {
    SleepingScene changed = s;
    BodySettings settings = s.world.bodySettings();
    changes[k](settings);
    ASSERT_TRUE(changed.world.setBodySettings(settings)) << "change " << k;
    EXPECT_EQ(changed.world.bodySettings(), settings) << "change " << k;
    EXPECT_FALSE(asleep(changed.world, s.lower)) << "change " << k;
    EXPECT_FALSE(asleep(changed.world, s.upper)) << "change " << k;
    EXPECT_FALSE(asleep(changed.world, s.apart)) << "change " << k;
  }
}

TEST(BodySleep, EveryRequestOnABodyWakesItsIsland) {
  const SleepingScene s = sleepingScene();
  ASSERT_TRUE(asleep(s.world, s.lower) && asleep(s.world, s.upper) && asleep(s.world, s.apart));
  const std::size_t upper = *s.world.bodies().find(s.upper);
  const Transform pose = s.world.bodies().pose(upper);
  const Vec3 top = pose.apply(Vec3(0.0, 0.0, 0.5));
  // Each request on the upper cube (or its hinge), made on a copy of the sleeping scene.
  const std::vector<std::pair<std::string, std::function<Status(World&)>>> requests = {
      {"setBodyPose", [&](World& w) { return w.setBodyPose(s.upper, pose); }},
      {"setBodyVelocity",
       [&](World& w) { return w.setBodyVelocity(s.upper, Vec3::Zero(), Vec3::Zero()); }},
      {"addBodyForce", [&](World& w) { return w.addBodyForce(s.upper, Vec3(0.1, 0, 0), top); }},
      {"addBodyTorque", [&](World& w) { return w.addBodyTorque(s.upper, Vec3(0, 0, 0.1)); }},
      {"applyBodyImpulse",
       [&](World& w) { return w.applyBodyImpulse(s.upper, Vec3(0.01, 0, 0), top); }},
      {"addJoint",
       [&](World& w) {
         return w
             .addJoint(
                 BallJoint{JointEnd::inWorld(top), JointEnd::onBody(s.upper, Vec3(0, 0, 0.5))})
             .status();
       }},
      {"removeJoint", [&](World& w) { return w.removeJoint(s.hinge); }},
      {"setHingeMotor", [&](World& w) { return w.setHingeMotor(s.hinge, true, 0.0, 1.0); }},
      {"wakeBody", [&](World& w) { return w.wakeBody(s.upper); }},
  };
  for (const auto& [name, request] : requests) {
    World world = s.world;
    ASSERT_TRUE(request(world)) << name;
    EXPECT_FALSE(asleep(world, s.upper)) << name;
    EXPECT_FALSE(asleep(world, s.lower)) << name << " (the other cube of the island)";
    EXPECT_TRUE(asleep(world, s.apart)) << name << " (another island)";
  }
}

TEST(BodySleep, AParticleHittingASleepingBodyWakesItsIsland) {
  // A 0.1 kg particle dropped from 0.5 m above the sleeping stack hits the upper cube at
  // 3 m/s: the stack wakes (both cubes), the box apart sleeps on.
  const SleepingScene s = sleepingScene();
  World world = s.world;
  ParticleSpec spec;
  spec.position = Vec3(0.1, 0.0, 2.5);
  spec.velocity = Vec3(0.0, 0.0, -3.0);
  spec.inverse_mass = 10.0;
  spec.radius = 0.05;
  ASSERT_TRUE(world.addParticle(spec));
  EXPECT_TRUE(asleep(world, s.upper));  // adding a particle touches no body
  int lower_woke = -1;
  int upper_woke = -1;
  bool apart_woke = false;
  for (int step = 1; step <= 30; ++step) {
    world.step();
    if (lower_woke < 0 && !asleep(world, s.lower)) lower_woke = step;
    if (upper_woke < 0 && !asleep(world, s.upper)) upper_woke = step;
    apart_woke = apart_woke || !asleep(world, s.apart);
  }
  // It reaches the cube's top (z = 2.05 for its centre) after 0.45 m at ~3 m/s: step 9 or so.
  std::printf("[ sleep ] particle on the sleeping stack: upper woke in step %d, lower in %d\n",
              upper_woke, lower_woke);
  EXPECT_GT(upper_woke, 0);
  EXPECT_LE(upper_woke, 12);
  EXPECT_EQ(lower_woke, upper_woke);
  EXPECT_FALSE(apart_woke);
}

// While a body moves, the world takes the bodies' substeps (4); once every body sleeps the grain
// resting on the box is the particle solver's alone and the world takes the particles' own (1),
// until the box wakes. The grain stays put through both changes, and the reports give the
// grain's weight over either substep.
TEST(BodySleep, AWorldWhoseBodiesAllSleepTakesTheParticlesSubsteps) {
  World world(config());
  addGround(world);
  const BodyId table = *world.addBody(body(box(Vec3::Constant(0.25)), 20.0, Vec3(0.0, 0.0, 0.25)));
  const ParticleId grain = addGrain(world, Vec3(0.0, 0.0, 0.5 + kGrainRadius));
  const auto grainWeight = [&]() {
    Real impulse = 0.0;
    for (const BodyContactReport& c : world.bodyContacts()) {
      if (c.other != BodyContactReport::Other::kParticle || c.particle != grain) continue;
      for (const auto& p : c.points) impulse += p.normal_impulse;
    }
    return impulse / (world.config().dt / world.substepsUsed());
  };
  const Real z = 0.5 + kGrainRadius;
  world.step();
  EXPECT_EQ(world.substepsUsed(), world.bodySettings().substeps);
  for (int step = 1; step < stepsToSleep(world) + 1; ++step) world.step();
  ASSERT_TRUE(asleep(world, table));
  world.step();
  EXPECT_EQ(world.substepsUsed(), world.config().substeps);
  EXPECT_NEAR(grainWeight(), 0.05 * kG, 1e-9);
  EXPECT_NEAR(world.particles().positions()(2, 0), z, 1e-6);
  ASSERT_TRUE(world.wakeBody(table));
  world.step();
  EXPECT_EQ(world.substepsUsed(), world.bodySettings().substeps);
  EXPECT_NEAR(grainWeight(), 0.05 * kG, 1e-9);
  for (int step = 0; step < 2 * stepsToSleep(world); ++step) {
    world.step();
    EXPECT_NEAR(world.particles().positions()(2, 0), z, 1e-6) << "step " << step;
  }
  EXPECT_TRUE(asleep(world, table));
  EXPECT_EQ(world.substepsUsed(), world.config().substeps);
}

// A box hung from the world sleeps; its joint's reaction is still its weight, the impulse the
// joint keeps over the body solver's substep, not over the particles' the world now takes.
TEST(BodySleep, AJointCarriesItsLoadWhileItsBodySleeps) {
  World world(config());
  const Real m = 2.0;
  const BodyId hung = *world.addBody(body(box(Vec3::Constant(0.1)), m, Vec3(0.0, 0.0, -1.0)));
  BallJoint joint;
  joint.a = JointEnd::inWorld(Vec3::Zero());
  joint.b = JointEnd::onBody(hung, Vec3(0.0, 0.0, 1.0));
  ASSERT_TRUE(world.addJoint(joint));
  for (int step = 0; step < 2 * stepsToSleep(world); ++step) world.step();
  ASSERT_TRUE(asleep(world, hung));
  EXPECT_EQ(world.substepsUsed(), world.config().substeps);
  ASSERT_EQ(world.jointReactions().size(), 1u);
  EXPECT_NEAR(world.jointReactions()[0].force.z(), m * kG, 1e-6 * m * kG);
}

// A bin of grains: 20 kg, a floor and four walls 0.5 m square inside, and 12 x 12 x 3 grains of
// 2.5 cm and 20 g dropped in from a block with a little jitter.
struct GrainBin {
  World world{config()};
  BodyId bin;
};

GrainBin grainBin() {
  GrainBin scene;
  World& world = scene.world;
  addGround(world, Material{0.1, 0.6});
  CollisionSettings collisions;
  collisions.particle_collisions = true;
  collisions.particle_restitution = 0.1;
  collisions.particle_friction = 0.3;
  EXPECT_TRUE(world.setCollisionSettings(collisions).isOk());
  const Material material{0.0, 0.6};
  BodySpec bin;
  bin.mass = 20.0;
  const auto add = [&](const Vec3& half_extents, const Vec3& at) {
    BodyShapeSpec shape = box(half_extents, material);
    shape.local.position = at;
    bin.shapes.push_back(shape);
  };
  const Real inside = 0.25;
  const Real wall = 0.05;
  const Real outer = inside + wall;
  add(Vec3(outer, outer, wall), Vec3(0.0, 0.0, wall));
  add(Vec3(wall, outer, 0.2), Vec3(outer, 0.0, 2.0 * wall + 0.2));
  add(Vec3(wall, outer, 0.2), Vec3(-outer, 0.0, 2.0 * wall + 0.2));
  add(Vec3(inside, wall, 0.2), Vec3(0.0, outer, 2.0 * wall + 0.2));
  add(Vec3(inside, wall, 0.2), Vec3(0.0, -outer, 2.0 * wall + 0.2));
  scene.bin = *world.addBody(bin);
  const Real r = 0.025;
  ParticleSpec grain;
  grain.radius = r;
  grain.inverse_mass = 50.0;
  for (int k = 0; k < 12 * 12 * 3; ++k) {
    const int i = k % 12;
    const int j = (k / 12) % 12;
    const int l = k / 144;
    // A fixed jitter of up to 2 mm, so the grains do not land in columns.
    const Real jitter = 0.002 * std::sin(1.7 * k);
    grain.position =
        Vec3(-inside + r + 0.041 * i + jitter, -inside + r + 0.041 * j - jitter, 0.15 + 0.055 * l);
    EXPECT_TRUE(world.addParticle(grain));
  }
  return scene;
}

// The bin falls asleep while its grains still settle (the slowest of them under the sleep speed);
// the world then takes the particles' substep, 4 times the bodies', and the pile passes to the
// particle solver without a jolt: it is handed over from the body rows in a step of the bodies'
// substeps, the pairs' impulses with it (the pile in the awake bin was the body solver's alone),
// and the particle solver's kept impulses are scaled to the longer substep. Handed over and
// lengthened in one step, the grains left it at 11 cm/s; with the impulses unscaled, at 9 cm/s;
// without the pairs' impulses, at 37 cm/s. Each woke the bin again. The pile then rests as the
// particle solver holds a pile: within its velocity tolerance (its passes stop once one changes
// less), a few grains at up to about 1e-4 m/s in place, moving some 30 um in 5 s (as grains of the
// 4,000-grain piles did before, in a bin of colliders or of bodies: docs/BENCHMARKS.md, session
// 31). Handed over in the same way before the pile was the body solver's alone, this one came to
// rest to rounding.
TEST(BodySleep, APileInABinThatFallsAsleepSettlesOnTheLongerSubstep) {
  GrainBin scene = grainBin();
  World& world = scene.world;
  const auto fastestGrain = [&world]() {
    return world.particles().velocities().colwise().norm().maxCoeff();
  };
  int slept = -1;
  for (int step = 0; step < 6 * 60 && slept < 0; ++step) {
    world.step();
    if (asleep(world, scene.bin)) slept = step;
  }
  ASSERT_GE(slept, 0) << "the bin never fell asleep";
  const Real when_asleep = fastestGrain();
  const Real tolerance = world.collisionSettings().velocity_tolerance;
  Real fastest = 0.0;
  bool stayed_asleep = true;
  Eigen::Matrix3Xd before_last;
  for (int step = 0; step < 8 * 60; ++step) {
    if (step == 3 * 60) before_last = world.particles().positions();
    world.step();
    fastest = std::max(fastest, fastestGrain());
    stayed_asleep = stayed_asleep && asleep(world, scene.bin);
  }
  const Real moved = (world.particles().positions() - before_last).colwise().norm().maxCoeff();
  std::printf(
      "[ sleep ] bin asleep after step %d, the grains then up to %.2e m/s, after it %.2e, at "
      "the end %.2e; the farthest moved %.2e m in the last 5 s\n",
      slept, when_asleep, fastest, fastestGrain(), moved);
  EXPECT_TRUE(stayed_asleep);
  EXPECT_LE(fastest, std::max(when_asleep, 10.0 * tolerance));
  EXPECT_EQ(world.substepsUsed(), world.config().substeps);
  EXPECT_LT(fastestGrain(), tolerance);
  EXPECT_LT(moved, 1e-4);
}

// The asleep bin's pile is the particle solver's; woken, it is the body solver's again, its pair
// rows starting from the particle solver's impulses (scaled to the body solver's substep), so the
// pile does not drop for a substep.
TEST(BodySleep, APileStaysAtRestWhenItsBinWakes) {
  GrainBin scene = grainBin();
  World& world = scene.world;
  for (int step = 0; step < 6 * 60 && !asleep(world, scene.bin); ++step) world.step();
  ASSERT_TRUE(asleep(world, scene.bin));
  for (int step = 0; step < 60; ++step) world.step();
  const Real before = world.particles().velocities().colwise().norm().maxCoeff();
  ASSERT_TRUE(world.wakeBody(scene.bin).isOk());
  Real fastest = 0.0;
  for (int step = 0; step < 10; ++step) {
    world.step();
    fastest = std::max(fastest, world.particles().velocities().colwise().norm().maxCoeff());
  }
  std::printf("[ sleep ] woken bin: the grains up to %.2e m/s before, %.2e after\n", before,
              fastest);
  EXPECT_LT(fastest, 10.0 * world.collisionSettings().velocity_tolerance);
}

// Awake (sleeping off), the bin carries its pile in the body solver alone: the particle solver's
// velocity passes have nothing of it left to solve, and the pile comes to rest. Both solvers on
// the pile undid each other's lateral pushes (the body rows had no friction): the particle solver
// ran all 20 of its passes every substep until 3.5 s.
TEST(BodySleep, APileInAnAwakeBinIsTheBodySolversAlone) {
  GrainBin scene = grainBin();
  World& world = scene.world;
  BodySettings settings = world.bodySettings();
  settings.sleep = false;
  ASSERT_TRUE(world.setBodySettings(settings).isOk());
  const auto fastestGrain = [&world]() {
    return world.particles().velocities().colwise().norm().maxCoeff();
  };
  for (int step = 0; step < 2 * 60; ++step) world.step();
  int most_passes = 0;
  for (int step = 0; step < 60; ++step) {
    world.step();
    most_passes = std::max(most_passes, world.lastContactStats().velocity_iterations);
  }
  for (int step = 0; step < 7 * 60; ++step) world.step();
  Real fastest = 0.0;
  for (int step = 0; step < 60; ++step) {
    world.step();
    fastest = std::max(fastest, fastestGrain());
  }
  std::printf(
      "[ sleep ] awake bin: at most %d velocity passes a substep from 2 s to 3 s, the grains up "
      "to %.2e m/s from 10 s to 11 s\n",
      most_passes, fastest);
  EXPECT_LE(most_passes, 2);
  EXPECT_LT(fastest, 1e-9);
}

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
