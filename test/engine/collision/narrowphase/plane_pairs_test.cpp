// Each shape against a half-space: the sphere's one point, the capsule's ends, the box's deepest
// corners. The plane is tilted; shapes are placed in its frame (z along its normal).
#include "manifold_checks.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

using namespace narrowphase_test;  // NOLINT

class NarrowphasePlane : public ::testing::Test {
 protected:
  const Vec3 normal_ = Vec3(1.0, 2.0, 2.0) / 3.0;
  const Real offset_ = 1.0;
  // The plane's frame: origin on it, z along its normal.
  const Frame plane_ = frameAt(offset_ * normal_, Quat::FromTwoVectors(Vec3::UnitZ(), normal_));

  template <typename Shape>
  Manifold onPlane(const Shape& shape, const Frame& local, const Real margin) const {
    return collideWithPlane(shape, moved(plane_, local), normal_, offset_, margin);
  }
  std::vector<Expected> world(std::vector<Expected> local) const {
    for (Expected& e : local) e.point = plane_.apply(e.point);
    return local;
  }
};

TEST_F(NarrowphasePlane, Sphere) {
  const SphereShape sphere{0.5};
  Manifold m = onPlane(sphere, frameAt(Vec3(0.3, 0.2, 0.45)), 0.0);
  expectNormal(m, -normal_);
  expectPoints(m, world({{Vec3(0.3, 0.2, -0.025), -0.05}}));
  m = onPlane(sphere, frameAt(Vec3(0.3, 0.2, 0.55)), 0.1);
  expectPoints(m, world({{Vec3(0.3, 0.2, 0.025), 0.05}}));
  EXPECT_EQ(onPlane(sphere, frameAt(Vec3(0.3, 0.2, 0.55)), 0.01).count, 0);
}

TEST_F(NarrowphasePlane, CapsuleLyingStandingAndTilted) {
  const CapsuleShape capsule{0.25, 1.0};
  Manifold m = onPlane(capsule, frameAt(Vec3(0, 0, 0.2), zToX()), 0.0);
  expectNormal(m, -normal_);
  expectPoints(m, world({{Vec3(-1, 0, -0.025), -0.05}, {Vec3(1, 0, -0.025), -0.05}}));
  EXPECT_EQ(sortedIds(m), (std::vector<std::uint32_t>{0, 1}));
  m = onPlane(capsule, frameAt(Vec3(0, 0, 1.2)), 0.0);
  expectPoints(m, world({{Vec3(0, 0, -0.025), -0.05}}));
  EXPECT_EQ(m.points[0].id, 0u);
  m = onPlane(capsule, frameAt(Vec3(0, 0, 1.2)), 3.0);
  expectPoints(m, world({{Vec3(0, 0, -0.025), -0.05}, {Vec3(0, 0, 0.975), 1.95}}));
  // Upside down: the end at local +z is the lower one.
  m = onPlane(capsule, frameAt(Vec3(0, 0, 1.2), about(Vec3::UnitX(), M_PI)), 0.0);
  ASSERT_EQ(m.count, 1);
  EXPECT_EQ(m.points[0].id, 1u);
}

TEST_F(NarrowphasePlane, BoxFlatOnEdgeAndOnCorner) {
  const BoxShape cube{Vec3::Constant(0.5)};
  Manifold m = onPlane(cube, frameAt(Vec3(0.1, 0.2, 0.49)), 0.0);
  expectNormal(m, -normal_);
  expectPoints(m, world({{Vec3(0.6, 0.7, -0.005), -0.01},
                         {Vec3(-0.4, 0.7, -0.005), -0.01},
                         {Vec3(0.6, -0.3, -0.005), -0.01},
                         {Vec3(-0.4, -0.3, -0.005), -0.01}}));
  EXPECT_EQ(sortedIds(m), (std::vector<std::uint32_t>{4, 5, 6, 7}));
  const Real root_half = std::sqrt(0.5);
  m = onPlane(cube, frameAt(Vec3(0.1, 0, root_half - 0.01), about(Vec3::UnitX(), M_PI / 4)), 0.0);
  expectPoints(m, world({{Vec3(0.6, 0, -0.005), -0.01}, {Vec3(-0.4, 0, -0.005), -0.01}}));
  // A corner down: corner 7 (-h, -h, -h) turned onto -z.
  const Quat corner_down = Quat::FromTwoVectors(Vec3::Ones().normalized(), Vec3::UnitZ());
  m = onPlane(cube, frameAt(Vec3(0, 0, std::sqrt(0.75) - 0.01), corner_down), 0.0);
  expectPoints(m, world({{Vec3(0, 0, -0.005), -0.01}}));
  EXPECT_EQ(m.points[0].id, 7u);
}

TEST_F(NarrowphasePlane, BoxKeepsItsDeepestFour) {
  const BoxShape cube{Vec3::Constant(0.5)};
  const Manifold m = onPlane(cube, frameAt(Vec3(0, 0, 0.1), about(Vec3::UnitY(), 0.05)), 2.0);
  ASSERT_EQ(m.count, 4);
  EXPECT_EQ(sortedIds(m), (std::vector<std::uint32_t>{4, 5, 6, 7}));
  for (int i = 0; i < 4; ++i) EXPECT_LT(m.points[i].separation, -0.3);
}

TEST_F(NarrowphasePlane, IdsSurviveANudge) {
  const BoxShape cube{Vec3::Constant(0.5)};
  const CapsuleShape capsule{0.25, 1.0};
  const Frame flat = moved(plane_, frameAt(Vec3(0.1, 0.2, 0.49)));
  const Frame lying = moved(plane_, frameAt(Vec3(0, 0, 0.2), zToX()));
  EXPECT_EQ(sortedIds(collideWithPlane(cube, flat, normal_, offset_, 0.0)),
            sortedIds(collideWithPlane(cube, nudged(flat), normal_, offset_, 0.0)));
  EXPECT_EQ(sortedIds(collideWithPlane(capsule, lying, normal_, offset_, 0.0)),
            sortedIds(collideWithPlane(capsule, nudged(lying), normal_, offset_, 0.0)));
}

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
