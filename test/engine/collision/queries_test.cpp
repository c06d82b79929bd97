#include <gtest/gtest.h>

#include "mass_aggregate_sim/engine/world/world.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

class Queries : public ::testing::Test {
 protected:
  void SetUp() override {
    ground_ = *world_.addCollider(PlaneCollider{});
    BoxCollider box;
    box.center = Vec3(5, 0, 0.5);
    box.half_extents = Vec3(0.5, 0.5, 0.5);
    box_ = *world_.addCollider(box);
    capsule_ = *world_.addCollider(CapsuleCollider{Vec3(0, 5, 0), Vec3(0, 5, 2), 0.25, Material{}});
    sphere_ = *world_.addCollider(SphereCollider{Vec3(-5, 0, 1), 0.5, Material{}});
    ParticleSpec spec;
    spec.position = Vec3(0, 0, 1);
    spec.radius = 0.1;
    particle_ = *world_.addParticle(spec);
  }
  World world_;
  ColliderId ground_ = 0;
  ColliderId box_ = 0;
  ColliderId capsule_ = 0;
  ColliderId sphere_ = 0;
  ParticleId particle_;
};

TEST_F(Queries, RayHitsTheNearestParticleOrCollider) {
  auto hit = world_.raycast(Vec3(0, 0, 5), Vec3(0, 0, -2), 100.0);  // direction is normalised
  ASSERT_TRUE(hit);
  EXPECT_TRUE(hit->hit_particle);
  EXPECT_EQ(hit->particle, particle_);
  EXPECT_NEAR(hit->distance, 3.9, 1e-12);
  EXPECT_NEAR((hit->point - Vec3(0, 0, 1.1)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((hit->normal - Vec3::UnitZ()).norm(), 0.0, 1e-12);

  hit = world_.raycast(Vec3(0, 0.5, 5), -Vec3::UnitZ(), 100.0);  // beside the particle: ground
  ASSERT_TRUE(hit);
  EXPECT_FALSE(hit->hit_particle);
  EXPECT_EQ(hit->collider, ground_);
  EXPECT_NEAR(hit->distance, 5.0, 1e-12);

  hit = world_.raycast(Vec3(1, 0, 0.5), Vec3::UnitX(), 100.0);
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->collider, box_);
  EXPECT_NEAR(hit->distance, 3.5, 1e-12);
  EXPECT_NEAR((hit->normal + Vec3::UnitX()).norm(), 0.0, 1e-12);

  hit = world_.raycast(Vec3(0, 0, 1.5), Vec3::UnitY(), 100.0);
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->collider, capsule_);
  EXPECT_NEAR(hit->distance, 4.75, 1e-12);

  hit = world_.raycast(Vec3(0, 0, 1), -Vec3::UnitX(), 100.0);  // starts inside the particle
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->collider, sphere_);
  EXPECT_NEAR(hit->distance, 4.5, 1e-12);
}

TEST_F(Queries, RayMissesAndBadInput) {
  EXPECT_FALSE(world_.raycast(Vec3(0, 0, 5), Vec3::UnitZ(), 100.0));          // up into nothing
  EXPECT_FALSE(world_.raycast(Vec3(0, 0, 5), -Vec3::UnitZ(), 3.0));           // too short
  EXPECT_FALSE(world_.raycast(Vec3(0, 0, 5), Vec3::Zero(), 100.0));           // no direction
  EXPECT_FALSE(world_.raycast(Vec3(0, 0, 5), -Vec3::UnitZ(), -1.0));          // negative reach
  EXPECT_FALSE(world_.raycast(Vec3(0, 0, std::nan("")), -Vec3::UnitZ(), 1));  // not finite
}

TEST(Overlap, SphereAndBoxFindTheParticlesTheyTouch) {
  World world;
  std::vector<ParticleId> ids;
  for (int i = 0; i < 10; ++i) {
    ParticleSpec spec;
    spec.position = Vec3(i, 0, 0);
    spec.radius = 0.25;
    ids.push_back(*world.addParticle(spec));
  }
  // Sphere of radius 1 at x = 4.5: centres 3.75..5.25 reach it (with the particles' radii).
  std::vector<ParticleId> found = world.overlapSphere(Vec3(4.5, 0, 0), 1.0);
  EXPECT_EQ(found, (std::vector<ParticleId>{ids[4], ids[5]}));
  found = world.overlapSphere(Vec3(4.5, 0, 0), 1.25);  // now touching 3 and 6 exactly
  EXPECT_EQ(found, (std::vector<ParticleId>{ids[3], ids[4], ids[5], ids[6]}));
  found = world.overlapBox(Vec3(2, 0, 0), Vec3(1, 1, 1));
  EXPECT_EQ(found, (std::vector<ParticleId>{ids[1], ids[2], ids[3]}));
  found = world.overlapBox(Vec3(2, 0, 1.2), Vec3(1, 1, 0.1));  // above the row by 0.1 + 0.25
  EXPECT_TRUE(found.empty());
  found = world.overlapBox(Vec3(2, 0, 1.2), Vec3(1, 1, 0.96));  // box bottom at 0.24
  EXPECT_EQ(found.size(), 3u);
}

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
