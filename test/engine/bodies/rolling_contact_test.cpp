// Round shapes rolling fast stay on what they roll on. A contact is found once a step and its
// separation is moved on between substeps by how far its anchors have moved. A ball's turn
// carries the material point below its centre up and away (by r (1 - cos theta)), but the ball's
// contact stays below its centre: read as the material point, a ball of 3 cm rolling at 3.4 m/s
// (1.9 rad a step) seemed to lift off within the step and sank 3.65 mm into the ground, where it
// rolled on with no impulse (the 2,000-sphere rain's deepest overlap, for seconds).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "body_scenes.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

using test_bodies::addGround;
using test_bodies::body;
using test_bodies::box;
using test_bodies::config;
using test_bodies::sphere;

// How a body rolling along x went over `steps`: the lowest and highest its centre was and its
// speed and spin at the end.
struct Roll {
  Real lowest = 1e9;
  Real highest = -1e9;
  Real speed = 0.0;
  Real spin = 0.0;  // about +y, the axis a body rolling along +x turns about
};

Roll roll(World& world, const BodyId id, const int steps) {
  Roll r;
  for (int step = 0; step < steps; ++step) {
    world.step();
    const std::size_t i = *world.bodies().find(id);
    r.lowest = std::min(r.lowest, world.bodies().position(i).z());
    r.highest = std::max(r.highest, world.bodies().position(i).z());
  }
  const std::size_t i = *world.bodies().find(id);
  r.speed = world.bodies().linearVelocity(i).norm();
  r.spin = world.bodies().angularVelocity(i).y();
  return r;
}

World worldWithoutSleep() {
  World world(config());
  BodySettings settings;
  settings.sleep = false;
  EXPECT_TRUE(world.setBodySettings(settings));
  return world;
}

// Rolling along +x without slipping at v: w = v / r about +y (w x (-r z) = v x).
BodySpec rolling(BodySpec spec, const Real v, const Real r) {
  spec.linear_velocity = Vec3(v, 0.0, 0.0);
  spec.angular_velocity = Vec3(0.0, v / r, 0.0);
  return spec;
}

constexpr Real kRadius = 0.03;
constexpr Real kSpeed = 3.4;
// Twice BodySettings::linear_slop: what a resting contact may settle into, and no bump.
constexpr Real kHeightTolerance = 1e-4;

TEST(RollingContact, AFastBallRollsOnTheGroundAtItsRadius) {
  World world = worldWithoutSleep();
  addGround(world);
  const BodyId id =
      *world.addBody(rolling(body(sphere(kRadius), 0.1, Vec3(0, 0, kRadius)), kSpeed, kRadius));
  const Roll r = roll(world, id, 120);
  std::printf("[ ball ] centre between %.4f and %.4f mm off its radius, v %.4f m/s, w r %.4f\n",
              1e3 * (r.lowest - kRadius), 1e3 * (r.highest - kRadius), r.speed, r.spin * kRadius);
  EXPECT_GT(r.lowest, kRadius - kHeightTolerance);
  EXPECT_LT(r.highest, kRadius + kHeightTolerance);
  // Rolling without slipping loses nothing to friction.
  EXPECT_NEAR(r.speed, kSpeed, 1e-3 * kSpeed);
  EXPECT_NEAR(r.spin * kRadius, kSpeed, 1e-3 * kSpeed);
}

// The ball on a fixed slab (a body, not a collider): the ball is side a of the contact when it
// was added first (the lower shape index), side b otherwise.
void rollOnASlab(const bool ball_first) {
  World world = worldWithoutSleep();
  BodySpec slab = body(box(Vec3(20.0, 20.0, 0.1)), 1.0, Vec3(0, 0, -0.1));
  slab.type = BodyType::kFixed;
  const BodySpec ball = rolling(body(sphere(kRadius), 0.1, Vec3(0, 0, kRadius)), kSpeed, kRadius);
  BodyId id;
  if (ball_first) {
    id = *world.addBody(ball);
    ASSERT_TRUE(world.addBody(slab));
  } else {
    ASSERT_TRUE(world.addBody(slab));
    id = *world.addBody(ball);
  }
  const Roll r = roll(world, id, 120);
  EXPECT_GT(r.lowest, kRadius - kHeightTolerance);
  EXPECT_LT(r.highest, kRadius + kHeightTolerance);
  EXPECT_NEAR(r.speed, kSpeed, 1e-3 * kSpeed);
}

TEST(RollingContact, AFastBallRollsOnAFixedSlabAsSideA) { rollOnASlab(true); }
TEST(RollingContact, AFastBallRollsOnAFixedSlabAsSideB) { rollOnASlab(false); }

// Rolling into a wall: the ball's contact with the wall's face stays level with its centre
// as it turns. Read as a point of the ball, the contact seemed to move away from the face
// within the step: this ball went 23.6 mm into the face, and in the rain 2 to 8 of the 2,000
// spheres went through the 0.2 m walls at ground level.
TEST(RollingContact, AFastBallRollingIntoAWallStopsAtIt) {
  World world = worldWithoutSleep();
  addGround(world);
  BodySpec wall = body(box(Vec3(0.1, 1.0, 1.0)), 1.0, Vec3(1.0, 0, 1.0));
  wall.type = BodyType::kFixed;
  ASSERT_TRUE(world.addBody(wall));
  const BodyId id =
      *world.addBody(rolling(body(sphere(kRadius), 0.1, Vec3(0, 0, kRadius)), kSpeed, kRadius));
  Real farthest = 0.0;
  for (int step = 0; step < 120; ++step) {
    world.step();
    farthest = std::max(farthest, world.bodies().position(*world.bodies().find(id)).x());
  }
  std::printf("[ wall ] the ball's centre got to %.4f mm from the face\n", 1e3 * (0.9 - farthest));
  EXPECT_LT(farthest, 0.9 - kRadius + kHeightTolerance);
}

// A capsule lying along y, rolling along x about its axis (w = v / r, 1 rad a step): its rounding
// is its radius about its segment, and its two contacts stay below the segment.
TEST(RollingContact, AFastCapsuleRollsOnItsSideAtItsRadius) {
  World world = worldWithoutSleep();
  addGround(world);
  const Real r = 0.05;
  const Real v = 3.0;
  BodyShapeSpec capsule;
  capsule.geometry = CapsuleShape{r, 0.2};
  capsule.material = Material{0.0, 0.5};
  const Quat along_y(Eigen::AngleAxis<Real>(0.5 * M_PI, Vec3::UnitX()));
  const BodyId id = *world.addBody(rolling(body(capsule, 1.0, Vec3(0, 0, r), along_y), v, r));
  const Roll rolled = roll(world, id, 120);
  std::printf("[ capsule ] centre between %.4f and %.4f mm off its radius, v %.4f m/s\n",
              1e3 * (rolled.lowest - r), 1e3 * (rolled.highest - r), rolled.speed);
  EXPECT_GT(rolled.lowest, r - kHeightTolerance);
  EXPECT_LT(rolled.highest, r + kHeightTolerance);
  EXPECT_NEAR(rolled.speed, v, 1e-3 * v);
}

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
