// Lockstep with bodies (issue 14's acceptance test 14): the same calls in the same order give the
// same bits, and a copy taken at any step, sleeping islands included, steps on as the original.
#include <gtest/gtest.h>

#include <cstdint>
#include <utility>
#include <vector>

#include "body_scenes.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

using namespace test_bodies;

constexpr int kSteps = 600;

// The handles a run's requests use; equal in every world built the same way.
struct Handles {
  std::vector<BodyId> stack;
  BodyId compound;
  BodyId pendulum;
  BodyId chain_a;
  BodyId chain_b;
  BodyId welded_a;
  BodyId welded_b;
  BodyId hanging;
  BodyId kinematic;
  BodyId shelf;
  ParticleId knot;
  std::vector<ParticleId> grains;
  JointId hinge = 0;
  JointId extra_joint = 0;
};

struct Lane {
  World world{config()};
  Handles ids;
};

BodyShapeSpec capsule(const Real radius, const Real half_length) {
  BodyShapeSpec s;
  s.geometry = CapsuleShape{radius, half_length};
  return s;
}

BodyShapeSpec at(BodyShapeSpec shape, const Vec3& position, const Quat& q = Quat::Identity()) {
  shape.local.position = position;
  shape.local.rotation = q;
  return shape;
}

// A plane and a box collider; a stack of three cubes on the plane with grains resting on its top
// (one on two others; particle collisions on);
// a compound (a box with a sphere and a turned capsule) landing on the box
// collider; a hinged pendulum with a motor; a ball-jointed pair hanging from the world; two bodies
// welded by a fixed joint; a box on a cable from a particle held by a rod; a kinematic body
// sweeping past; a fixed shelf with a grain on it.
void build(Lane& run) {
  World& w = run.world;
  Handles& ids = run.ids;
  addGround(w);
  BoxCollider block;
  block.center = Vec3(4.0, 0.0, 0.5);
  block.half_extents = Vec3(1.0, 1.0, 0.5);
  block.orientation = Quat(Eigen::AngleAxisd(0.2, Vec3::UnitZ()));
  block.material = Material{0.1, 0.6};
  ASSERT_TRUE(w.addCollider(block));
  for (int k = 0; k < 3; ++k) {
    ids.stack.push_back(
        *w.addBody(body(box(Vec3::Constant(0.25)), 1.0, Vec3(0, 0, 0.25 + 0.5 * k))));
  }
  for (int k = 0; k < 3; ++k) ids.grains.push_back(addGrain(w, Vec3(0.1 * k - 0.1, 0.0, 1.56)));
  // One more on the two on the left: with particle collisions, the grains' contacts are rows of
  // the body solver too, warm started across steps.
  ids.grains.push_back(addGrain(w, Vec3(-0.05, 0.0, 1.56 + 0.087)));
  CollisionSettings collisions;
  collisions.particle_collisions = true;
  ASSERT_TRUE(w.setCollisionSettings(collisions));

  BodySpec compound;
  compound.shapes = {box(Vec3(0.3, 0.2, 0.1)), at(sphere(0.15), Vec3(0.3, 0.0, 0.1)),
                     at(capsule(0.08, 0.2), Vec3(-0.25, 0.0, 0.1),
                        Quat(Eigen::AngleAxisd(M_PI / 2.0, Vec3::UnitY())))};
  compound.shapes[1].density = 500.0;
  compound.pose.position = Vec3(4.0, 0.0, 1.6);
  compound.pose.rotation = Quat(Eigen::AngleAxisd(0.3, Vec3(1.0, 1.0, 0.0).normalized()));
  compound.angular_velocity = Vec3(0.0, 0.0, 1.0);
  compound.linear_damping = 0.05;
  // Added twice and the first removed, so a slot is reused by what follows.
  const BodyId first = *w.addBody(compound);
  ids.compound = *w.addBody(compound);
  ASSERT_TRUE(w.removeBody(first));

  ids.pendulum = *w.addBody(body(box(Vec3(0.05, 0.05, 0.4)), 1.0, Vec3(-3.0, 0.0, 2.6)));
  HingeJoint hinge;
  hinge.a = JointEnd::inWorld(Vec3(-3.0, 0.0, 3.0));
  hinge.b = JointEnd::onBody(ids.pendulum, Vec3(0.0, 0.0, 0.4));
  hinge.axis = Vec3::UnitY();
  hinge.limit = true;
  hinge.lower = -1.0;
  hinge.upper = 1.2;
  hinge.motor = true;
  hinge.motor_speed = 1.5;
  hinge.max_motor_torque = 2.0;
  ids.hinge = *w.addJoint(hinge);

  ids.chain_a = *w.addBody(body(sphere(0.15), 0.5, Vec3(-1.0, 2.0, 2.5)));
  ids.chain_b = *w.addBody(body(capsule(0.1, 0.2), 0.5, Vec3(-0.6, 2.0, 2.5)));
  ASSERT_TRUE(w.addJoint(
      BallJoint{JointEnd::inWorld(Vec3(-1.0, 2.0, 3.0)), JointEnd::onBody(ids.chain_a)}));
  ASSERT_TRUE(w.addJoint(BallJoint{JointEnd::onBody(ids.chain_a, Vec3(0.2, 0.0, 0.0)),
                                   JointEnd::onBody(ids.chain_b, Vec3(-0.2, 0.0, 0.0))}));

  ids.welded_a = *w.addBody(body(box(Vec3::Constant(0.2)), 1.0, Vec3(2.0, -2.0, 1.0)));
  ids.welded_b = *w.addBody(body(sphere(0.2), 1.0, Vec3(2.5, -2.0, 1.0)));
  ASSERT_TRUE(w.addJoint(FixedJoint{JointEnd::onBody(ids.welded_a),
                                    JointEnd::onBody(ids.welded_b, Vec3(-0.5, 0.0, 0.0))}));
  ASSERT_TRUE(w.setBodyVelocity(ids.welded_a, Vec3(0.5, 0.0, 1.0), Vec3(0.0, 2.0, 0.0)));

  ParticleSpec knot;
  knot.position = Vec3(0.0, -3.0, 2.0);
  knot.inverse_mass = 10.0;
  knot.radius = 0.05;
  ids.knot = *w.addParticle(knot);
  ASSERT_TRUE(w.addLink(Rod::anchoredAt(ids.knot, Vec3(0.0, -3.0, 3.0), 1.0)));
  ids.hanging = *w.addBody(body(box(Vec3::Constant(0.1)), 2.0, Vec3(0.0, -3.0, 1.4)));
  ASSERT_TRUE(w.addJoint(DistanceJoint::cable(
      JointEnd::atParticle(ids.knot), JointEnd::onBody(ids.hanging, Vec3(0, 0, 0.1)), 0.5)));
  ASSERT_TRUE(w.addJoint(
      DistanceJoint::rod(JointEnd::inWorld(Vec3(0.8, -3.0, 2.0)), JointEnd::onBody(ids.hanging))));

  BodySpec kinematic = body(box(Vec3(0.2, 0.2, 0.2)), 0.0, Vec3(-2.0, -1.0, 0.3));
  kinematic.type = BodyType::kKinematic;
  kinematic.linear_velocity = Vec3(0.4, 0.0, 0.0);
  ids.kinematic = *w.addBody(kinematic);

  BodySpec shelf = body(box(Vec3(0.5, 0.5, 0.05)), 0.0, Vec3(-2.0, 2.5, 1.0));
  shelf.type = BodyType::kFixed;
  ids.shelf = *w.addBody(shelf);
  ids.grains.push_back(addGrain(w, Vec3(-2.0, 2.5, 1.2)));
}

// The requests of a run, by step: impulses, removals, new joints and bodies, poses, velocities,
// forces, motors; one wakes a sleeping island.
void request(Lane& run, const int step) {
  World& w = run.world;
  Handles& ids = run.ids;
  switch (step) {
    case 40:
      ASSERT_TRUE(w.applyBodyImpulse(ids.chain_b, Vec3(0.0, 0.5, 0.0), Vec3(-0.6, 2.0, 2.6)));
      break;
    case 90:
      ASSERT_TRUE(w.applyImpulse(ids.knot, Vec3(0.05, 0.0, 0.0)));
      break;
    case 150:
      ASSERT_TRUE(w.setHingeMotor(ids.hinge, true, -2.0, 3.0));
      break;
    case 200: {
      const JointEnd a = JointEnd::onBody(ids.welded_b, Vec3(0.2, 0.0, 0.0));
      const JointEnd b = JointEnd::atParticle(ids.grains.back());
      const auto id = w.addJoint(DistanceJoint::cable(a, b));
      ASSERT_TRUE(id);
      ids.extra_joint = *id;
      break;
    }
    case 260:
      // Wakes the welded pair (asleep by now) and knocks the stack.
      ASSERT_TRUE(w.applyBodyImpulse(ids.welded_a, Vec3(0.0, 0.3, 0.5), Vec3(2.0, -2.0, 1.2)));
      ASSERT_TRUE(w.applyBodyImpulse(ids.stack.back(), Vec3(0.2, 0.0, 0.0), Vec3(0, 0, 1.3)));
      break;
    case 300:
      ASSERT_TRUE(w.removeBody(ids.chain_a));
      break;
    case 330: {
      Transform pose;
      pose.position = Vec3(4.2, 0.3, 1.5);
      pose.rotation = Quat(Eigen::AngleAxisd(0.7, Vec3::UnitX()));
      ASSERT_TRUE(w.setBodyPose(ids.compound, pose));
      break;
    }
    case 360:
      ASSERT_TRUE(w.setBodyVelocity(ids.kinematic, Vec3(-0.3, 0.1, 0.0), Vec3(0.0, 0.0, 0.5)));
      break;
    case 400: {
      const auto id = w.addBody(body(capsule(0.1, 0.3), 1.0, Vec3(0.0, 0.0, 2.5),
                                     Quat(Eigen::AngleAxisd(0.4, Vec3::UnitY()))));
      ASSERT_TRUE(id);
      ASSERT_TRUE(w.addJoint(BallJoint{JointEnd::onBody(*id, Vec3(0, 0, 0.4)),
                                       JointEnd::inWorld(Vec3(0.0, 0.0, 2.9))}));
      break;
    }
    case 450:
      ASSERT_TRUE(w.removeJoint(ids.extra_joint));
      ASSERT_TRUE(w.addJoint(HingeJoint{JointEnd::onBody(ids.welded_a),
                                        JointEnd::inWorld(Vec3(2.0, -2.0, 2.0)), Vec3::UnitX()}));
      break;
    case 500:
      ASSERT_TRUE(w.removeParticle(ids.knot));
      break;
    default:
      break;
  }
  if (step >= 470 && step < 490) {
    ASSERT_TRUE(w.addBodyForce(ids.compound, Vec3(0.0, 3.0, 0.0), Vec3(4.0, 0.0, 1.0)));
    ASSERT_TRUE(w.addBodyTorque(ids.hanging, Vec3(0.0, 0.0, 0.05)));
  }
}

// Steps a run from its current step to kSteps with the requests due before each step.
void runTo(Lane& run, const int until, std::vector<std::uint64_t>* trace = nullptr) {
  while (static_cast<int>(run.world.stepCount()) < until) {
    request(run, static_cast<int>(run.world.stepCount()));
    run.world.step();
    if (trace) trace->push_back(run.world.stateHash());
  }
}

int sleeping(const World& world) {
  int n = 0;
  for (std::size_t i = 0; i < world.bodies().size(); ++i) {
    n += world.bodies().dynamic(i) && !world.bodies().awake(i) ? 1 : 0;
  }
  return n;
}

// The reference run: a hash after every step, and how many bodies slept after each.
struct Reference {
  std::vector<std::uint64_t> hashes;
  std::vector<int> asleep;
};

const Reference& reference() {
  static const Reference ref = [] {
    Reference r;
    Lane run;
    build(run);
    while (static_cast<int>(run.world.stepCount()) < kSteps) {
      runTo(run, static_cast<int>(run.world.stepCount()) + 1, &r.hashes);
      r.asleep.push_back(sleeping(run.world));
    }
    EXPECT_EQ(run.world.divergenceCount(), 0u);
    return r;
  }();
  return ref;
}

// The scene does what the copies below rely on: islands (the compound, the welded pair) sleep
// before the impulse at 260, one wakes with it, and some sleep again at 440.
TEST(LockstepBodies, IslandsSleepAndWake) {
  const Reference& ref = reference();
  ASSERT_EQ(ref.hashes.size(), static_cast<std::size_t>(kSteps));
  EXPECT_GE(ref.asleep[249], 3);
  EXPECT_LT(ref.asleep[261], ref.asleep[249]);
  EXPECT_GE(ref.asleep[439], 3);
}

TEST(LockstepBodies, TwoWorldsGivenTheSameCallsStayBitIdentical) {
  Lane a;
  Lane b;
  build(a);
  build(b);
  ASSERT_EQ(a.world.stateHash(), b.world.stateHash());
  for (int step = 0; step < kSteps; ++step) {
    runTo(a, step + 1);
    runTo(b, step + 1);
    ASSERT_EQ(a.world.stateHash(), b.world.stateHash()) << "after step " << step + 1;
    ASSERT_EQ(a.world.stateHash(), reference().hashes[step]) << "after step " << step + 1;
  }
  EXPECT_EQ(a.world.bodies().size(), b.world.bodies().size());
  EXPECT_EQ(a.world.joints().size(), b.world.joints().size());
  EXPECT_EQ(a.world.divergenceCount(), 0u);
}

class LockstepBodiesCopy : public ::testing::TestWithParam<int> {};

// A copy constructed and a copy assigned (over a world with a scene of its own) at the given step
// step on, with the same requests, through the same hashes as the reference run.
TEST_P(LockstepBodiesCopy, ACopyStepsOnToTheSameHashes) {
  const int at = GetParam();
  const Reference& ref = reference();
  Lane original;
  build(original);
  runTo(original, at);
  if (at > 0) {
    std::printf("[ lockstep ] copy at step %d: %d bodies asleep\n", at, ref.asleep[at - 1]);
  }
  Lane copied{World(original.world), original.ids};
  Lane assigned;
  build(assigned);
  runTo(assigned, 17);
  assigned.world = original.world;
  assigned.ids = original.ids;
  for (Lane* run : {&copied, &assigned}) {
    ASSERT_EQ(run->world.stateHash(), original.world.stateHash());
    ASSERT_EQ(sleeping(run->world), sleeping(original.world));
  }
  for (int step = at; step < kSteps; ++step) {
    for (Lane* run : {&original, &copied, &assigned}) {
      runTo(*run, step + 1);
      ASSERT_EQ(run->world.stateHash(), ref.hashes[step]) << "after step " << step + 1;
    }
  }
}

// Before any step, while everything moves, while the stack sleeps (twice: before and after it
// was woken), and late.
INSTANTIATE_TEST_SUITE_P(AtSteps, LockstepBodiesCopy, ::testing::Values(0, 130, 250, 440, 590));

TEST(LockstepBodies, AMovedFromWorldIsUsable) {
  Lane run;
  build(run);
  runTo(run, 120);
  const std::uint64_t hash = run.world.stateHash();
  World moved(std::move(run.world));
  EXPECT_EQ(moved.stateHash(), hash);
  // The moved-from world: clear() and step() work, and it takes a scene again.
  run.world.clear();
  run.world.step();
  EXPECT_EQ(run.world.bodies().size(), 0u);
  Lane fresh;
  build(fresh);
  run.world = fresh.world;
  run.world.step();
  fresh.world.step();
  EXPECT_EQ(run.world.stateHash(), fresh.world.stateHash());
  // Moved from by assignment, then stepped without a clear first.
  World target;
  target = std::move(run.world);
  run.world.step();
  run.world.clear();
  run.world.step();
  const auto id = run.world.addBody(body(sphere(0.2), 1.0, Vec3(0.0, 0.0, 1.0)));
  ASSERT_TRUE(id);
  for (int step = 0; step < 10; ++step) run.world.step();
  EXPECT_LT(run.world.bodies().position(*run.world.bodies().find(*id)).z(), 1.0);
  EXPECT_EQ(run.world.divergenceCount(), 0u);
  // What moved on steps on as the reference does.
  Lane rest{std::move(moved), run.ids};
  runTo(rest, kSteps);
  EXPECT_EQ(rest.world.stateHash(), reference().hashes.back());
}

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
