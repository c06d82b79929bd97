#include <gtest/gtest.h>

#include "mass_aggregate_sim/engine/world/world.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

// The case: a 1 cm particle (radius 5 mm) at 1000 m/s, dt = 1/60 s (16.7 m a step),
// against obstacles 1 cm thick.
constexpr Real kRadius = 0.005;
constexpr Real kSpeed = 1000.0;

World bulletWorld(const bool continuous, const bool particle_collisions = false) {
  World world;  // dt = 1/60, no gravity
  CollisionSettings settings;
  settings.continuous = continuous;
  settings.particle_collisions = particle_collisions;
  EXPECT_TRUE(world.setCollisionSettings(settings).isOk());
  return world;
}

ParticleId fireBullet(World& world, const Vec3& from = Vec3(-1.0, 0.0, 0.0)) {
  ParticleSpec spec;
  spec.position = from;
  spec.velocity = Vec3(kSpeed, 0.0, 0.0);
  spec.radius = kRadius;
  return *world.addParticle(spec);
}

enum class Obstacle { kBox, kOrientedBox, kSphere, kCapsule, kPlane };

void addObstacle(World& world, const Obstacle obstacle) {
  const Material material{0.5, 0.0};
  switch (obstacle) {
    case Obstacle::kBox: {
      BoxCollider wall;
      wall.half_extents = Vec3(0.005, 1.0, 1.0);  // 1 cm thick
      wall.material = material;
      ASSERT_TRUE(world.addCollider(wall).isOk());
      break;
    }
    case Obstacle::kOrientedBox: {
      BoxCollider wall;
      wall.half_extents = Vec3(1.0, 0.005, 1.0);  // 1 cm thick along its y, turned onto x
      wall.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitZ()));
      wall.material = material;
      ASSERT_TRUE(world.addCollider(wall).isOk());
      break;
    }
    case Obstacle::kSphere:
      ASSERT_TRUE(world.addCollider(SphereCollider{Vec3::Zero(), 0.005, material}).isOk());
      break;
    case Obstacle::kCapsule:
      ASSERT_TRUE(world.addCollider(CapsuleCollider{Vec3(0, -1, 0), Vec3(0, 1, 0), 0.005, material})
                      .isOk());
      break;
    case Obstacle::kPlane:
      ASSERT_TRUE(world.addCollider(PlaneCollider{-Vec3::UnitX(), 0.0, material}).isOk());  // x > 0
      break;
  }
}

class Tunnelling : public ::testing::TestWithParam<Obstacle> {};

TEST_P(Tunnelling, ThinObstacleStopsAFastParticleOnlyWithContinuousDetection) {
  {
    World world = bulletWorld(false);
    addObstacle(world, GetParam());
    fireBullet(world);
    world.step();
    // Without swept tests the thin obstacles are jumped over; the half-space is not, as a
    // particle deep inside it is pushed back out.
    const Real x = world.particles().positions()(0, 0);
    if (GetParam() != Obstacle::kPlane) {
      EXPECT_GT(x, 10.0);
    }
  }
  World world = bulletWorld(true);
  addObstacle(world, GetParam());
  fireBullet(world);
  world.step();
  EXPECT_EQ(world.lastContactStats().ccd_hits, 1u);
  // Stopped on the near side at the time of impact and bounced back with e = 0.5.
  const Vec3 x = world.particles().positions().col(0);
  const Vec3 v = world.particles().velocities().col(0);
  EXPECT_LT(x.x(), 0.0);
  EXPECT_GT(x.x(), -0.011 - 1e-9);
  EXPECT_NEAR(v.x(), -0.5 * kSpeed, 1e-9);
  for (int s = 0; s < 10; ++s) world.step();
  EXPECT_LT(world.particles().positions()(0, 0), -40.0);  // still flying back
}

INSTANTIATE_TEST_SUITE_P(EveryShape, Tunnelling,
                         ::testing::Values(Obstacle::kBox, Obstacle::kOrientedBox,
                                           Obstacle::kSphere, Obstacle::kCapsule,
                                           Obstacle::kPlane));

TEST(ContinuousDetection, FastParticleHitsAnotherParticle) {
  for (const bool continuous : {false, true}) {
    World world = bulletWorld(continuous, true);
    CollisionSettings settings = world.collisionSettings();
    settings.particle_restitution = 1.0;
    ASSERT_TRUE(world.setCollisionSettings(settings).isOk());
    const ParticleId bullet = fireBullet(world);
    ParticleSpec target;
    target.radius = kRadius;
    const ParticleId hit = *world.addParticle(target);
    const Vec3 momentum = world.linearMomentum();
    world.step();
    const Vec3 v_bullet = world.particles().velocities().col(*world.particles().find(bullet));
    const Vec3 v_target = world.particles().velocities().col(*world.particles().find(hit));
    if (continuous) {
      // Equal masses, e = 1: the bullet stops and the target takes its velocity.
      EXPECT_NEAR(v_bullet.norm(), 0.0, 1e-9);
      EXPECT_NEAR((v_target - Vec3(kSpeed, 0, 0)).norm(), 0.0, 1e-9);
    } else {
      EXPECT_EQ(v_target.norm(), 0.0);  // passed straight through
    }
    EXPECT_NEAR((world.linearMomentum() - momentum).norm(), 0.0, 1e-9);
  }
}

TEST(ContinuousDetection, BulletStaysBetweenTwoThinWalls) {
  World world = bulletWorld(true);
  for (const Real x : {-1.0, 1.0}) {
    BoxCollider wall;
    wall.center = Vec3(x, 0, 0);
    wall.half_extents = Vec3(0.005, 1.0, 1.0);
    wall.material = Material{1.0, 0.0};
    ASSERT_TRUE(world.addCollider(wall).isOk());
  }
  fireBullet(world, Vec3::Zero());
  for (int s = 0; s < 600; ++s) {
    world.step();
    ASSERT_LT(std::abs(world.particles().positions()(0, 0)), 1.0) << "step " << s;
  }
  EXPECT_NEAR(world.particles().velocities().col(0).norm(), kSpeed, 1e-6);
}

TEST(ContinuousDetection, SlowParticlesAreNotSwept) {
  World world = bulletWorld(true);
  addObstacle(world, Obstacle::kBox);
  ParticleSpec slow;
  slow.position = Vec3(-0.2, 0, 0);
  slow.velocity = Vec3(0.1, 0, 0);  // 1.7 mm a step: less than its radius
  slow.radius = kRadius;
  ASSERT_TRUE(world.addParticle(slow).isOk());
  world.step();
  EXPECT_EQ(world.lastContactStats().ccd_hits, 0u);
}

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
