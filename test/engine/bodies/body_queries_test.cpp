// Ray casts and overlap queries see bodies: the nearest of particles, bodies and colliders.
#include <gtest/gtest.h>

#include "body_scenes.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

using namespace test_bodies;

TEST(BodyQueries, ARayHitsTheNearestOfBodiesParticlesAndColliders) {
  World world(config());
  addGround(world);
  const Quat turn(Eigen::AngleAxisd(M_PI / 4.0, Vec3::UnitZ()));
  const BodyId cube =
      *world.addBody(body(box(Vec3::Constant(0.5)), 1.0, Vec3(3.0, 0.0, 1.0), turn));
  ParticleSpec p;
  p.position = Vec3(6.0, 0.0, 1.0);
  p.radius = 0.2;
  ASSERT_TRUE(world.addParticle(p));
  // Along x from the origin at z = 1: the cube's edge (turned 45 degrees) at x = 3 - sqrt(0.5).
  auto hit = world.raycast(Vec3(0.0, 0.0, 1.0), Vec3::UnitX(), 100.0);
  ASSERT_TRUE(hit);
  EXPECT_TRUE(hit->hit_body);
  EXPECT_EQ(hit->body, cube);
  EXPECT_NEAR(hit->distance, 3.0 - std::sqrt(0.5), 1e-12);
  // Beyond the cube the particle; straight down the ground.
  hit = world.raycast(Vec3(5.0, 0.0, 1.0), Vec3::UnitX(), 100.0);
  ASSERT_TRUE(hit);
  EXPECT_TRUE(hit->hit_particle);
  EXPECT_NEAR(hit->distance, 0.8, 1e-12);
  hit = world.raycast(Vec3(-2.0, 0.0, 1.0), -Vec3::UnitZ(), 100.0);
  ASSERT_TRUE(hit);
  EXPECT_FALSE(hit->hit_body);
  EXPECT_FALSE(hit->hit_particle);
  EXPECT_NEAR(hit->distance, 1.0, 1e-12);
  // Too short to reach anything.
  EXPECT_FALSE(world.raycast(Vec3(0.0, 0.0, 1.0), Vec3::UnitX(), 1.0));
}

TEST(BodyQueries, OverlapQueriesFindBodiesByTheirShapes) {
  World world(config(0.0));
  const BodyId ball = *world.addBody(body(sphere(0.5), 1.0, Vec3(0.0, 0.0, 0.0)));
  const BodyId cube = *world.addBody(body(box(Vec3::Constant(0.5)), 1.0, Vec3(5.0, 0.0, 0.0)));
  EXPECT_EQ(world.bodiesOverlappingSphere(Vec3(0.9, 0.0, 0.0), 0.5), std::vector<BodyId>{ball});
  EXPECT_TRUE(world.bodiesOverlappingSphere(Vec3(1.1, 0.0, 0.0), 0.5).empty());
  EXPECT_EQ(world.bodiesOverlappingBox(Vec3(4.0, 0.0, 0.0), Vec3::Constant(0.6)),
            std::vector<BodyId>{cube});
  EXPECT_EQ(world.bodiesOverlappingBox(Vec3(2.5, 0.0, 0.0), Vec3(2.5, 0.1, 0.1)).size(), 2u);
  EXPECT_TRUE(world.bodiesOverlappingSphere(Vec3::Zero(), -1.0).empty());  // refused: nothing
}

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
