// Determinism with bodies: a fixed scene of bodies, joints and particles, some of whose islands
// fall asleep, stepped a fixed number of times gives a stated state hash (see
// golden_hash_test.cpp for when and how to restate it).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "../bodies/body_scenes.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

using namespace test_bodies;

constexpr std::uint64_t kBodiesGoldenHash = 0x933ceeeef8a48200ull;
constexpr int kBodiesGoldenSteps = 600;

// A stack of three boxes (asleep by the end), a hinged rod swinging, a chain of three spheres on
// ball joints hanging from the world, a capsule rolling, and grains falling onto a box that
// rests on the ground.
World bodiesGoldenScene() {
  World world(config());
  addGround(world);
  for (int k = 0; k < 3; ++k) {
    EXPECT_TRUE(world.addBody(body(box(Vec3::Constant(0.5)), 1.0, Vec3(-3.0, 0.0, 0.5 + k))));
  }
  const BodyId rod = *world.addBody(body(box(Vec3(0.5, 0.05, 0.05)), 1.0, Vec3(0.5, -3.0, 3.0),
                                         Quat(Eigen::AngleAxis<Real>(0.3, Vec3::UnitY()))));
  HingeJoint hinge;
  hinge.a = JointEnd::inWorld(Vec3(0.0, -3.0, 3.0 + 0.5 * std::sin(0.3)));
  hinge.b = JointEnd::onBody(rod, Vec3(-0.5, 0.0, 0.0));
  hinge.axis = Vec3::UnitY();
  EXPECT_TRUE(world.addJoint(hinge));
  BodyId above;
  for (int k = 0; k < 3; ++k) {
    const BodyId ball =
        *world.addBody(body(sphere(0.15), 0.5, Vec3(3.0 + 0.4 * (k + 1), 3.0, 4.0)));
    BallJoint joint;
    joint.a = k == 0 ? JointEnd::inWorld(Vec3(3.0, 3.0, 4.0))
                     : JointEnd::onBody(above, Vec3(0.2, 0.0, 0.0));
    joint.b = JointEnd::onBody(ball, Vec3(-0.2, 0.0, 0.0));
    EXPECT_TRUE(world.addJoint(joint));
    above = ball;
  }
  BodyShapeSpec capsule;
  capsule.geometry = CapsuleShape{0.2, 0.4};
  // Lying along y, rolling along x.
  BodySpec rolling = body(capsule, 2.0, Vec3(0.0, 3.0, 0.2),
                          Quat(Eigen::AngleAxis<Real>(0.5 * M_PI, Vec3::UnitX())));
  rolling.linear_velocity = Vec3(1.0, 0.0, 0.0);
  EXPECT_TRUE(world.addBody(rolling));
  EXPECT_TRUE(world.addBody(body(box(Vec3(0.6, 0.6, 0.25)), 4.0, Vec3(3.0, -3.0, 0.25))));
  ParticleSpec grain;
  grain.radius = 0.08;
  grain.inverse_mass = 5.0;
  for (int k = 0; k < 6; ++k) {
    grain.position = Vec3(2.7 + 0.12 * k, -3.0 + 0.05 * (k % 2), 1.0 + 0.3 * k);
    EXPECT_TRUE(world.addParticle(grain));
  }
  return world;
}

TEST(GoldenHash, BodiesJointsParticlesAndSleepGiveTheStatedHash) {
  World world = bodiesGoldenScene();
  for (int step = 0; step < kBodiesGoldenSteps; ++step) world.step();
  const BodyStore& bodies = world.bodies();
  int asleep = 0;
  for (std::size_t i = 0; i < bodies.size(); ++i) asleep += bodies.awake(i) ? 0 : 1;
  std::printf("[ golden ] bodies hash 0x%016llx after %d steps, %d of %zu bodies asleep\n",
              static_cast<unsigned long long>(world.stateHash()), kBodiesGoldenSteps, asleep,
              bodies.size());
  EXPECT_EQ(world.divergenceCount(), 0u);
  EXPECT_GE(asleep, 3);                                // the stack at least
  EXPECT_LT(asleep, static_cast<int>(bodies.size()));  // the pendulums swing on
  EXPECT_EQ(world.stateHash(), kBodiesGoldenHash)
      << "body arithmetic changed; see the comment at the top of golden_hash_test.cpp";
}

TEST(GoldenHash, TheBodiesSceneIsTheSameEveryTime) {
  World a = bodiesGoldenScene();
  World b = bodiesGoldenScene();
  for (int step = 0; step < 200; ++step) {
    a.step();
    b.step();
    ASSERT_EQ(a.stateHash(), b.stateHash()) << "step " << step;
  }
}

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
