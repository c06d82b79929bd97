// The sphere's pair functions: against a sphere, a box (face, edge, corner, centre inside) and a
// capsule.
#include "manifold_checks.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

using namespace narrowphase_test;  // NOLINT

TEST(NarrowphaseSphereSphere, TouchingOverlappingAndSeparated) {
  const Vec3 u = Vec3(1.0, 2.0, 2.0) / 3.0;
  const SphereShape a{1.0};
  const SphereShape b{0.5};
  const Frame fa = frameAt(Vec3::Zero());
  Manifold m = collide(a, fa, b, frameAt(1.5 * u), 0.0);
  expectNormal(m, u);
  expectPoints(m, {{u, 0.0}});
  m = collide(a, fa, b, frameAt(1.4 * u), 0.0);
  expectNormal(m, u);
  expectPoints(m, {{0.95 * u, -0.1}});  // surfaces at 1.0 u and 0.9 u
  m = collide(a, fa, b, frameAt(1.55 * u), 0.1);
  expectPoints(m, {{1.025 * u, 0.05}});
  EXPECT_EQ(collide(a, fa, b, frameAt(1.55 * u), 0.01).count, 0);
}

TEST(NarrowphaseSphereSphere, ConcentricGivesUpAndNoNaN) {
  const Manifold m = collide(SphereShape{1.0}, frameAt(Vec3(1, 2, 3)), SphereShape{0.5},
                             frameAt(Vec3(1, 2, 3)), 0.0);
  ASSERT_TRUE(finiteUnitNormal(m));
  expectNormal(m, Vec3::UnitZ());
  expectPoints(m, {{Vec3(1, 2, 3.25), -1.5}});
}

class NarrowphaseSphereBox : public ::testing::Test {
 protected:
  const BoxShape box_{Vec3(1.0, 2.0, 3.0)};
  const Frame fb_ = frameAt(Vec3(0.5, -1.0, 2.0), about(Vec3(1, 1, 0), 0.6));
  Vec3 world(const Vec3& local) const { return fb_.apply(local); }
  Vec3 worldDirection(const Vec3& local) const { return fb_.rotation * local; }
  Manifold against(const Real r, const Vec3& local_centre, const Real margin) const {
    return collide(SphereShape{r}, frameAt(world(local_centre)), box_, fb_, margin);
  }
};

TEST_F(NarrowphaseSphereBox, Face) {
  const Manifold m = against(0.5, Vec3(1.3, 0.5, 0.2), 0.0);
  expectNormal(m, -worldDirection(Vec3::UnitX()));
  expectPoints(m, {{world(Vec3(0.9, 0.5, 0.2)), -0.2}});
}

TEST_F(NarrowphaseSphereBox, EdgeAndCornerWithinAndBeyondMargin) {
  const Vec3 o(0.6, 0.8, 0.0);
  Manifold m = against(0.6, Vec3(1.3, 2.4, 0.0), 0.0);
  expectNormal(m, -worldDirection(o));
  expectPoints(m, {{world(Vec3(1.0, 2.0, 0.0) - 0.05 * o), -0.1}});
  const Vec3 diagonal = Vec3::Ones().normalized();
  const Vec3 corner(1.0, 2.0, 3.0);
  m = against(0.2, corner + 0.3 * diagonal, 0.15);
  expectNormal(m, -worldDirection(diagonal));
  expectPoints(m, {{world(corner + 0.05 * diagonal), 0.1}});
  EXPECT_EQ(against(0.2, corner + 0.3 * diagonal, 0.05).count, 0);
}

TEST_F(NarrowphaseSphereBox, CentreInsideLeavesThroughTheNearestFace) {
  const Manifold m = against(0.25, Vec3(0.9, 0.5, 0.0), 0.0);
  expectNormal(m, -worldDirection(Vec3::UnitX()));
  // Surfaces at x = 0.9 - 0.25 (the sphere's) and 1.0 (the face).
  expectPoints(m, {{world(Vec3(0.825, 0.5, 0.0)), -0.35}});
}

TEST_F(NarrowphaseSphereBox, MovesWithBothShapes) {
  const SphereShape sphere{0.6};
  const Frame fa = frameAt(world(Vec3(1.3, 2.4, 0.1)));
  const Frame motion = someMotion();
  expectMovesWith(collide(sphere, fa, box_, fb_, 0.0),
                  collide(sphere, moved(motion, fa), box_, moved(motion, fb_), 0.0), motion);
}

TEST(NarrowphaseSphereBoxDegenerate, CentreAtTheBoxCentre) {
  const Manifold m = collide(SphereShape{0.5}, frameAt(Vec3::Zero()), BoxShape{Vec3::Ones()},
                             frameAt(Vec3::Zero()), 0.0);
  ASSERT_TRUE(finiteUnitNormal(m));
  expectNormal(m, -Vec3::UnitX());
  expectPoints(m, {{Vec3(0.25, 0.0, 0.0), -1.5}});
}

TEST(NarrowphaseSphereCapsule, SideEndAndMargin) {
  const CapsuleShape capsule{0.5, 1.0};
  const Frame fb = frameAt(Vec3::Zero(), zToX());  // ends at x = +-1
  const SphereShape sphere{0.5};
  Manifold m = collide(sphere, frameAt(Vec3(0.3, 0, 1.2)), capsule, fb, 0.25);
  expectNormal(m, -Vec3::UnitZ());
  expectPoints(m, {{Vec3(0.3, 0, 0.6), 0.2}});
  EXPECT_EQ(collide(sphere, frameAt(Vec3(0.3, 0, 1.2)), capsule, fb, 0.1).count, 0);
  m = collide(sphere, frameAt(Vec3(0.3, 0, 0.8)), capsule, fb, 0.0);
  expectNormal(m, -Vec3::UnitZ());
  expectPoints(m, {{Vec3(0.3, 0, 0.4), -0.2}});
  m = collide(sphere, frameAt(Vec3(1.6, 0, 0)), capsule, fb, 0.0);
  expectNormal(m, -Vec3::UnitX());
  expectPoints(m, {{Vec3(1.3, 0, 0), -0.4}});
}

TEST(NarrowphaseSphereCapsule, CentreOnTheAxisLeavesAcrossIt) {
  const Frame fb = frameAt(Vec3::Zero(), zToX());
  const Manifold m =
      collide(SphereShape{0.5}, frameAt(Vec3(0.2, 0, 0)), CapsuleShape{0.5, 1.0}, fb, 0.0);
  ASSERT_TRUE(finiteUnitNormal(m));
  expectNormal(m, fb.rotation.col(0));
  EXPECT_NEAR(m.points[0].separation, -1.0, kTolerance);
}

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
