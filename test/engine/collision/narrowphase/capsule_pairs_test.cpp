// Capsule against capsule: crossing, end to end, side by side (two points), degenerate.
#include "manifold_checks.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

using namespace narrowphase_test;  // NOLINT

// A: radius 0.5 along world x, ends at x = +-1.
const CapsuleShape kA{0.5, 1.0};
const Frame kFa = frameAt(Vec3::Zero(), zToX());

TEST(NarrowphaseCapsuleCapsule, CrossingGivesOnePoint) {
  const Manifold m =
      collide(kA, kFa, CapsuleShape{0.5, 1.0}, frameAt(Vec3(0, 0, 0.9), zToY()), 0.0);
  expectNormal(m, Vec3::UnitZ());
  expectPoints(m, {{Vec3(0, 0, 0.45), -0.1}});
}

TEST(NarrowphaseCapsuleCapsule, EndToEndGivesOnePoint) {
  const Manifold m =
      collide(kA, kFa, CapsuleShape{0.5, 1.0}, frameAt(Vec3(2.9, 0, 0), zToX()), 0.0);
  expectNormal(m, Vec3::UnitX());
  expectPoints(m, {{Vec3(1.45, 0, 0), -0.1}});
}

TEST(NarrowphaseCapsuleCapsule, SideBySideGivesTwoPoints) {
  const CapsuleShape b{0.5, 0.5};
  Manifold m = collide(kA, kFa, b, frameAt(Vec3(0.2, 0, 0.9), zToX()), 0.0);
  expectNormal(m, Vec3::UnitZ());
  expectPoints(m, {{Vec3(-0.3, 0, 0.45), -0.1}, {Vec3(0.7, 0, 0.45), -0.1}});
  expectDistinctIds(m);
  // Turned end for end: the same points.
  m = collide(kA, kFa, b, frameAt(Vec3(0.2, 0, 0.9), about(Vec3::UnitY(), -M_PI / 2)), 0.0);
  expectPoints(m, {{Vec3(-0.3, 0, 0.45), -0.1}, {Vec3(0.7, 0, 0.45), -0.1}});
  // Overlapping A's end: the stretch from B's end to A's end.
  m = collide(kA, kFa, CapsuleShape{0.5, 1.0}, frameAt(Vec3(1.5, 0, 0.9), zToX()), 0.0);
  expectPoints(m, {{Vec3(0.5, 0, 0.45), -0.1}, {Vec3(1.0, 0, 0.45), -0.1}});
  expectDistinctIds(m);
}

TEST(NarrowphaseCapsuleCapsule, SideBySideWithinAndBeyondMargin) {
  const CapsuleShape b{0.5, 0.5};
  const Frame fb = frameAt(Vec3(0.2, 0, 1.05), zToX());
  expectPoints(collide(kA, kFa, b, fb, 0.1),
               {{Vec3(-0.3, 0, 0.525), 0.05}, {Vec3(0.7, 0, 0.525), 0.05}});
  EXPECT_EQ(collide(kA, kFa, b, fb, 0.01).count, 0);
}

TEST(NarrowphaseCapsuleCapsule, NearlyParallelGivesTwoPointsEachAtItsOwnSeparation) {
  const CapsuleShape b{0.5, 0.5};
  const Real tilt = 0.005;
  const Frame fb = frameAt(Vec3(0.2, 0, 0.9), about(Vec3::UnitY(), tilt) * zToX());
  const Vec3 half = fb.rotation.col(2) * 0.5;
  std::vector<Expected> expected;
  for (const Vec3& end : {Vec3(fb.position - half), Vec3(fb.position + half)}) {
    expected.push_back({Vec3(end.x(), 0.0, 0.5 * end.z()), end.z() - 1.0});
  }
  const Manifold m = collide(kA, kFa, b, fb, 0.0);
  expectNormal(m, Vec3::UnitZ());
  expectPoints(m, expected);
  // Tilted well beyond parallel: one point, at B's lower end.
  const Frame steep = frameAt(Vec3(0.2, 0, 1.0), about(Vec3::UnitY(), 0.1) * zToX());
  EXPECT_EQ(collide(kA, kFa, b, steep, 0.0).count, 1);
}

TEST(NarrowphaseCapsuleCapsule, SideBySideIdsSurviveANudge) {
  const CapsuleShape b{0.5, 1.0};  // as long as A: its ends sit on A's
  const Frame fb = frameAt(Vec3(0, 0, 0.95), zToX());
  const Manifold m = collide(kA, kFa, b, fb, 0.0);
  ASSERT_EQ(m.count, 2);
  for (const Real amount : {1e-6, -1e-6}) {
    const Manifold nudged_m = collide(kA, kFa, b, nudged(fb, amount), 0.0);
    ASSERT_EQ(nudged_m.count, 2);
    EXPECT_EQ(sortedIds(m), sortedIds(nudged_m));
  }
  const Frame motion = someMotion();
  expectMovesWith(m, collide(kA, moved(motion, kFa), b, moved(motion, fb), 0.0), motion);
}

TEST(NarrowphaseCapsuleCapsule, SegmentsThatMeetLeaveAcrossBoth) {
  const Manifold m = collide(kA, kFa, CapsuleShape{0.5, 1.0}, frameAt(Vec3::Zero(), zToY()), 0.0);
  ASSERT_TRUE(finiteUnitNormal(m));
  expectNormal(m, Vec3::UnitZ());
  expectPoints(m, {{Vec3::Zero(), -1.0}});
}

TEST(NarrowphaseCapsuleCapsule, CoincidentAndZeroLengthGiveNoNaN) {
  Manifold m = collide(kA, kFa, kA, kFa, 0.0);
  ASSERT_TRUE(finiteUnitNormal(m));
  ASSERT_GE(m.count, 1);
  EXPECT_NEAR(m.normal.dot(Vec3::UnitX()), 0.0, kTolerance);  // across the axis
  for (int i = 0; i < m.count; ++i) EXPECT_NEAR(m.points[i].separation, -1.0, kTolerance);
  const CapsuleShape dot{0.5, 0.0};
  m = collide(dot, frameAt(Vec3(1, 2, 3)), dot, frameAt(Vec3(1, 2, 3)), 0.0);
  ASSERT_TRUE(finiteUnitNormal(m));
  expectPoints(m, {{Vec3(1, 2, 3), -1.0}});
  // A zero-length capsule is a ball.
  m = collide(dot, frameAt(Vec3(0.3, 0, 0.9)), kA, kFa, 0.0);
  expectNormal(m, -Vec3::UnitZ());
  expectPoints(m, {{Vec3(0.3, 0, 0.45), -0.1}});
}

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
