// Capsule against box: lying on a face (two points, clipped at the face's edges), standing on it,
// beside an edge, through the box, and degenerate.
#include "manifold_checks.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

using namespace narrowphase_test;  // NOLINT

// The box (half extents 2 x 1 x 0.5) is placed by a frame with no special axes; the capsule is
// given in the box's frame and moved with it, so every expectation below is in box coordinates.
class NarrowphaseCapsuleBox : public ::testing::Test {
 protected:
  const BoxShape box_{Vec3(2.0, 1.0, 0.5)};
  const Frame fb_ = frameAt(Vec3(0.4, -0.3, 1.1), about(Vec3(0.2, 1.0, 0.4), 0.5));

  Manifold collideLocal(const CapsuleShape& capsule, const Frame& local, const Real margin) const {
    return collide(capsule, moved(fb_, local), box_, fb_, margin);
  }
  Vec3 world(const Vec3& local) const { return fb_.apply(local); }
  Vec3 worldDirection(const Vec3& local) const { return fb_.rotation * local; }
  std::vector<Expected> world(std::vector<Expected> local) const {
    for (Expected& e : local) e.point = world(e.point);
    return local;
  }
};

TEST_F(NarrowphaseCapsuleBox, LyingOnAFaceGivesTwoPoints) {
  const CapsuleShape capsule{0.25, 1.0};
  // Bottom of the capsule at z = 0.45, the face at 0.5.
  const Manifold m = collideLocal(capsule, frameAt(Vec3(0.3, 0.1, 0.7), zToX()), 0.0);
  expectNormal(m, -worldDirection(Vec3::UnitZ()));
  expectPoints(m, world({{Vec3(-0.7, 0.1, 0.475), -0.05}, {Vec3(1.3, 0.1, 0.475), -0.05}}));
  expectDistinctIds(m);
}

TEST_F(NarrowphaseCapsuleBox, LyingOverTheFacesEdgeIsClippedThere) {
  const CapsuleShape capsule{0.25, 1.0};
  const Manifold m = collideLocal(capsule, frameAt(Vec3(1.5, 0.1, 0.7), zToX()), 0.0);
  expectNormal(m, -worldDirection(Vec3::UnitZ()));
  expectPoints(m, world({{Vec3(0.5, 0.1, 0.475), -0.05}, {Vec3(2.0, 0.1, 0.475), -0.05}}));
  expectDistinctIds(m);
}

TEST_F(NarrowphaseCapsuleBox, HoveringWithinAndBeyondMargin) {
  const CapsuleShape capsule{0.25, 1.0};
  const Frame local = frameAt(Vec3(0.3, 0.1, 0.8), zToX());
  expectPoints(collideLocal(capsule, local, 0.1),
               world({{Vec3(-0.7, 0.1, 0.525), 0.05}, {Vec3(1.3, 0.1, 0.525), 0.05}}));
  EXPECT_EQ(collideLocal(capsule, local, 0.01).count, 0);
}

TEST_F(NarrowphaseCapsuleBox, StandingOnAFaceGivesItsLowerEnd) {
  const CapsuleShape capsule{0.25, 1.0};
  const Manifold m = collideLocal(capsule, frameAt(Vec3(0.2, 0.1, 1.7)), 0.0);
  expectNormal(m, -worldDirection(Vec3::UnitZ()));
  expectPoints(m, world({{Vec3(0.2, 0.1, 0.475), -0.05}}));
}

TEST_F(NarrowphaseCapsuleBox, BesideAnEdge) {
  // Along y beside the edge x = 2, z = 0.5, nearest it along (0.6, 0, 0.8).
  const CapsuleShape capsule{0.6, 0.5};
  const Manifold m = collideLocal(capsule, frameAt(Vec3(2.3, 0.0, 0.9), zToY()), 0.0);
  const Vec3 o(0.6, 0.0, 0.8);
  expectNormal(m, -worldDirection(o));
  ASSERT_EQ(m.count, 1);
  EXPECT_NEAR(m.points[0].separation, -0.1, kTolerance);
  // Surfaces at the edge (2, y, 0.5) and 0.1 inside it; y anywhere along the capsule.
  const Vec3 local = fb_.applyInverse(m.points[0].point);
  EXPECT_TRUE((Vec3(local.x(), 0.0, local.z()) - (Vec3(2.0, 0.0, 0.5) - 0.05 * o)).norm() <=
              kTolerance);
  EXPECT_LE(std::abs(local.y()), 0.5);
}

TEST_F(NarrowphaseCapsuleBox, ThroughTheBoxLeavesTheShortWay) {
  // A thin capsule along x right through the box, 0.2 below its top face.
  const CapsuleShape capsule{0.1, 3.0};
  const Manifold m = collideLocal(capsule, frameAt(Vec3(0.0, 0.2, 0.3), zToX()), 0.0);
  expectNormal(m, -worldDirection(Vec3::UnitZ()));
  // Surfaces at z = 0.2 (the capsule's, r below its axis) and 0.5 (the face).
  expectPoints(m, world({{Vec3(-2.0, 0.2, 0.35), -0.3}, {Vec3(2.0, 0.2, 0.35), -0.3}}));
}

TEST_F(NarrowphaseCapsuleBox, EndInsideTheBox) {
  const CapsuleShape capsule{0.1, 0.5};
  // Standing, its lower end 0.2 under the top face.
  const Manifold m = collideLocal(capsule, frameAt(Vec3(0.1, 0.2, 0.8)), 0.0);
  expectNormal(m, -worldDirection(Vec3::UnitZ()));
  expectPoints(m, world({{Vec3(0.1, 0.2, 0.35), -0.3}}));
}

TEST_F(NarrowphaseCapsuleBox, AcrossAnEdgeLeavesAlongTheDiagonal) {
  // The segment crosses the edge x = 0 .. , y = 1, z = 0.5 diagonally, delta inside it.
  const Real delta = 0.01;
  const CapsuleShape capsule{0.1, 1.0};
  const Vec3 out = Vec3(0.0, 1.0, 1.0).normalized();
  const Vec3 edge_point(0.3, 1.0, 0.5);
  const Quat along = Quat::FromTwoVectors(Vec3::UnitZ(), Vec3(0.0, 1.0, -1.0));
  const Manifold m = collideLocal(capsule, frameAt(edge_point - delta * out, along), 0.0);
  expectNormal(m, -worldDirection(out));
  expectPoints(m, world({{Vec3(edge_point - 0.5 * (delta + 0.1) * out), -(delta + 0.1)}}));
}

TEST_F(NarrowphaseCapsuleBox, IdsSurviveANudgeAndTheContactMovesWithTheShapes) {
  const CapsuleShape capsule{0.25, 1.0};
  for (const Frame& local : {frameAt(Vec3(0.3, 0.1, 0.7), zToX()),
                             frameAt(Vec3(1.5, 0.1, 0.7), zToX()), frameAt(Vec3(0.2, 0.1, 1.7))}) {
    const Frame fa = moved(fb_, local);
    const Manifold m = collide(capsule, fa, box_, fb_, 0.0);
    const Manifold n = collide(capsule, nudged(fa), box_, fb_, 0.0);
    ASSERT_GE(m.count, 1);
    EXPECT_EQ(sortedIds(m), sortedIds(n));
    const Frame motion = someMotion();
    expectMovesWith(m, collide(capsule, moved(motion, fa), box_, moved(motion, fb_), 0.0), motion);
  }
}

TEST_F(NarrowphaseCapsuleBox, DegenerateInputsGiveNoNaN) {
  for (const CapsuleShape& capsule : {CapsuleShape{0.3, 0.0}, CapsuleShape{0.3, 1.0}}) {
    for (const Vec3& at : {Vec3(0, 0, 0), Vec3(2.0, 1.0, 0.5), Vec3(0.0, 0.0, 0.5)}) {
      const Manifold m = collideLocal(capsule, frameAt(at), 0.0);
      EXPECT_TRUE(finiteUnitNormal(m)) << at.transpose();
      EXPECT_GE(m.count, 1);
    }
  }
}

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
