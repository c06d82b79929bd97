// Box against box: resting flat, turned 45 degrees (a clipped octagon), on an edge, edges
// crossing, deep overlaps, margins, and ids that survive a nudge.
#include <set>

#include "engine/collision/narrowphase/face_clip.h"
#include "engine/collision/narrowphase/point_reduction.h"
#include "manifold_checks.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

using namespace narrowphase_test;  // NOLINT

const BoxShape kGround{Vec3(2.0, 2.0, 0.5)};
const BoxShape kCube{Vec3(0.5, 0.5, 0.5)};
const Real kRootHalf = std::sqrt(0.5);

// The area of the convex polygon made by the points (in a plane z = const).
Real quadrilateralArea(const Manifold& m) {
  // Order the points by angle about their centroid, then sum the triangle fan.
  Vec3 centre = Vec3::Zero();
  for (int i = 0; i < m.count; ++i) centre += m.points[i].point / m.count;
  std::vector<Vec3> p;
  for (int i = 0; i < m.count; ++i) p.push_back(m.points[i].point - centre);
  std::sort(p.begin(), p.end(), [](const Vec3& a, const Vec3& b) {
    return std::atan2(a.y(), a.x()) < std::atan2(b.y(), b.x());
  });
  Real area = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) area += p[i].cross(p[(i + 1) % p.size()]).z();
  return 0.5 * area;
}

TEST(NarrowphaseBoxBox, RestingFlatGivesFourCorners) {
  const Frame fa = frameAt(Vec3::Zero());
  const Frame fb = frameAt(Vec3(0.3, 0.2, 0.99));
  const Manifold m = collide(kGround, fa, kCube, fb, 0.0);
  expectNormal(m, Vec3::UnitZ());
  expectPoints(m, {{Vec3(0.8, 0.7, 0.495), -0.01},
                   {Vec3(-0.2, 0.7, 0.495), -0.01},
                   {Vec3(-0.2, -0.3, 0.495), -0.01},
                   {Vec3(0.8, -0.3, 0.495), -0.01}});
  expectDistinctIds(m);
  // The other way round: the same points, the normal flipped.
  const Manifold r = collide(kCube, fb, kGround, fa, 0.0);
  expectNormal(r, -Vec3::UnitZ());
  expectPoints(r, {{Vec3(0.8, 0.7, 0.495), -0.01},
                   {Vec3(-0.2, 0.7, 0.495), -0.01},
                   {Vec3(-0.2, -0.3, 0.495), -0.01},
                   {Vec3(0.8, -0.3, 0.495), -0.01}});
  const Frame motion = someMotion();
  expectMovesWith(m, collide(kGround, moved(motion, fa), kCube, moved(motion, fb), 0.0), motion);
}

TEST(NarrowphaseBoxBox, WithinAndBeyondMargin) {
  const Frame fa = frameAt(Vec3::Zero());
  const Frame fb = frameAt(Vec3(0.3, 0.2, 1.05));
  const Manifold m = collide(kGround, fa, kCube, fb, 0.1);
  expectNormal(m, Vec3::UnitZ());
  expectPoints(m, {{Vec3(0.8, 0.7, 0.525), 0.05},
                   {Vec3(-0.2, 0.7, 0.525), 0.05},
                   {Vec3(-0.2, -0.3, 0.525), 0.05},
                   {Vec3(0.8, -0.3, 0.525), 0.05}});
  EXPECT_EQ(collide(kGround, fa, kCube, fb, 0.01).count, 0);
  EXPECT_EQ(collide(kGround, fa, kCube, frameAt(Vec3(3.0, 0.0, 0.9)), 0.1).count, 0);
}

TEST(NarrowphaseBoxBox, EqualBoxesStackedKeepTheirIdsWhenNudged) {
  const Frame fa = frameAt(Vec3::Zero());
  const Frame fb = frameAt(Vec3(0.0, 0.0, 0.99));
  const Manifold m = collide(kCube, fa, kCube, fb, 0.0);
  expectNormal(m, Vec3::UnitZ());
  expectPoints(m, {{Vec3(0.5, 0.5, 0.495), -0.01},
                   {Vec3(-0.5, 0.5, 0.495), -0.01},
                   {Vec3(-0.5, -0.5, 0.495), -0.01},
                   {Vec3(0.5, -0.5, 0.495), -0.01}});
  for (const Frame& other : {nudged(fb), nudged(fb, -1e-6)}) {
    const Manifold n = collide(kCube, fa, kCube, other, 0.0);
    EXPECT_EQ(sortedIds(m), sortedIds(n));
    for (int i = 0; i < n.count; ++i) EXPECT_NEAR(n.points[i].separation, -0.01, 1e-5);
  }
}

TEST(NarrowphaseBoxBox, OffsetEqualBoxesKeepTheirReferenceFaceWhenTilted) {
  // Tilting B one way or the other makes its bottom face's axis separate the boxes a little more
  // than A's top face's (by the offset times the tilt); the reference face stays A's.
  const Frame fa = frameAt(Vec3::Zero());
  const Frame fb = frameAt(Vec3(0.2, 0.1, 0.99));
  const Manifold m = collide(kCube, fa, kCube, fb, 0.0);
  ASSERT_EQ(m.count, 4);
  for (const Vec3& axis : {Vec3(1, 0, 0), Vec3(0, 1, 0)}) {
    for (const Real tilt : {1e-6, -1e-6}) {
      const Frame tilted = frameAt(fb.position, about(axis, tilt));
      EXPECT_EQ(sortedIds(m), sortedIds(collide(kCube, fa, kCube, tilted, 0.0)));
    }
  }
}

TEST(NarrowphaseBoxBox, TurnedFortyFiveDegreesGivesFourOfTheOctagon) {
  const Frame fa = frameAt(Vec3::Zero());
  const Frame fb = frameAt(Vec3(0.0, 0.0, 0.98), about(Vec3::UnitZ(), M_PI / 4));
  const Manifold m = collide(kCube, fa, kCube, fb, 0.0);
  expectNormal(m, Vec3::UnitZ());
  ASSERT_EQ(m.count, 4);
  const Real a = kRootHalf - 0.5;  // where the turned square's sides cross the other's
  std::vector<Vec3> octagon;
  for (const Real sx : {1.0, -1.0}) {
    for (const Real sy : {1.0, -1.0}) {
      octagon.emplace_back(sx * 0.5, sy * a, 0.49);
      octagon.emplace_back(sx * a, sy * 0.5, 0.49);
    }
  }
  for (int i = 0; i < m.count; ++i) {
    EXPECT_NEAR(m.points[i].separation, -0.02, kTolerance);
    bool on_octagon = false;
    for (const Vec3& v : octagon) on_octagon |= (m.points[i].point - v).norm() <= kTolerance;
    EXPECT_TRUE(on_octagon) << m.points[i].point.transpose();
  }
  expectDistinctIds(m);
  // The largest quadrilateral on the octagon's corners: every other corner, a square whose side
  // joins (0.5, a) and (-a, 0.5).
  const Real side_squared = (0.5 + a) * (0.5 + a) + (0.5 - a) * (0.5 - a);
  EXPECT_NEAR(quadrilateralArea(m), side_squared, 1e-12);
  // Tilts every way: the deepest corner changes, the chosen four do not.
  for (const Vec3& axis : {Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 0), Vec3(1, -1, 0)}) {
    for (const Real amount : {1e-6, -1e-6}) {
      EXPECT_EQ(sortedIds(m), sortedIds(collide(kCube, fa, kCube, nudged(fb, amount, axis), 0.0)));
    }
  }
}

TEST(NarrowphaseBoxBox, OnItsEdgeGivesTheEdgesTwoEnds) {
  const Frame fa = frameAt(Vec3::Zero());
  const Frame fb = frameAt(Vec3(0.1, 0.0, 0.5 + kRootHalf - 0.01), about(Vec3::UnitX(), M_PI / 4));
  const Manifold m = collide(kGround, fa, kCube, fb, 0.0);
  expectNormal(m, Vec3::UnitZ());
  expectPoints(m, {{Vec3(0.6, 0.0, 0.495), -0.01}, {Vec3(-0.4, 0.0, 0.495), -0.01}});
  for (const Frame& other : {nudged(fb), nudged(fb, -1e-6)}) {
    EXPECT_EQ(sortedIds(m), sortedIds(collide(kGround, fa, kCube, other, 0.0)));
  }
}

TEST(NarrowphaseBoxBox, ALongEdgeLyingAcrossAFaceTouchesAtBothEndsOfTheFace) {
  // A 2 m beam on its edge across the unit cube's top face, 2 mm deep at the middle, that edge
  // tilted by a hair about y. The face axis overstates the overlap by the overhang, so an edge
  // pair (the beam's edge across one of the cube's top edges) separates them by less; its one
  // point would sit at one end of the face and jump to the other when the tilt turns.
  const BoxShape beam{Vec3(1.0, 0.2, 0.2)};
  const auto beamTilted = [](const Real degrees) {
    return frameAt(Vec3(0.0, 0.1, 0.5 + 0.2 * std::sqrt(2.0) - 0.002),
                   about(Vec3::UnitY(), degrees * M_PI / 180.0) * about(Vec3::UnitX(), M_PI / 4));
  };
  for (const Real degrees : {0.05, 0.2, -0.2}) {
    SCOPED_TRACE(degrees);
    const Manifold m = collide(kCube, frameAt(Vec3::Zero()), beam, beamTilted(degrees), 0.02);
    expectNormal(m, Vec3::UnitZ());
    // The beam's edge lies 0.5 tan(tilt) lower at x = +0.5 than at its middle, higher at -0.5
    // (and 0.28 (1 / cos(tilt) - 1) lower throughout: under 2e-6 m).
    const Real drop = 0.5 * std::tan(degrees * M_PI / 180.0);
    expectPoints(m,
                 {{Vec3(0.5, 0.1, 0.5 - 0.5 * (0.002 + drop)), -0.002 - drop},
                  {Vec3(-0.5, 0.1, 0.5 - 0.5 * (0.002 - drop)), -0.002 + drop}},
                 2e-6);
  }
  // Beyond the band (1 degree, sine 0.017) the edge pair stands: one point, at the deeper end.
  const Manifold m = collide(kCube, frameAt(Vec3::Zero()), beam, beamTilted(1.0), 0.02);
  ASSERT_EQ(m.count, 1);
  EXPECT_NEAR(m.points[0].point.x(), 0.5, 1e-3);
  EXPECT_NEAR(m.points[0].separation, -0.002 - 0.5 * std::tan(M_PI / 180.0), 1e-4);
}

TEST(NarrowphaseBoxBox, CrossingEdgesGiveOnePoint) {
  // A's top edge runs along x at z = sqrt(1/2); B's bottom edge along y, 0.01 lower.
  const Frame fa = frameAt(Vec3::Zero(), about(Vec3::UnitX(), M_PI / 4));
  const Frame fb = frameAt(Vec3(0, 0, 2 * kRootHalf - 0.01), about(Vec3::UnitY(), M_PI / 4));
  const Manifold m = collide(kCube, fa, kCube, fb, 0.0);
  expectNormal(m, Vec3::UnitZ());
  expectPoints(m, {{Vec3(0, 0, kRootHalf - 0.005), -0.01}});
  EXPECT_EQ(collide(kCube, fa, kCube, nudged(fb), 0.0).points[0].id, m.points[0].id);
  const Manifold r = collide(kCube, fb, kCube, fa, 0.0);
  expectNormal(r, -Vec3::UnitZ());
  expectPoints(r, {{Vec3(0, 0, kRootHalf - 0.005), -0.01}});
  const Frame motion = someMotion();
  expectMovesWith(m, collide(kCube, moved(motion, fa), kCube, moved(motion, fb), 0.0), motion);
}

TEST(NarrowphaseBoxBox, DeepOverlapLeavesTheShortWay) {
  const Manifold m =
      collide(kCube, frameAt(Vec3::Zero()), kCube, frameAt(Vec3(0.1, 0.0, 0.3)), 0.0);
  expectNormal(m, Vec3::UnitZ());
  // B's bottom face (z = -0.2) clipped at x = 0.5; the points midway up to A's top (0.5).
  expectPoints(m, {{Vec3(0.5, 0.5, 0.15), -0.7},
                   {Vec3(-0.4, 0.5, 0.15), -0.7},
                   {Vec3(-0.4, -0.5, 0.15), -0.7},
                   {Vec3(0.5, -0.5, 0.15), -0.7}});
}

TEST(NarrowphaseBoxBox, CoincidentBoxesGiveNoNaN) {
  for (const Real turn : {0.0, 0.5}) {
    const Manifold m = collide(kCube, frameAt(Vec3(1, 2, 3)), kCube,
                               frameAt(Vec3(1, 2, 3), about(Vec3::UnitZ(), turn)), 0.0);
    ASSERT_TRUE(finiteUnitNormal(m));
    ASSERT_GE(m.count, 1);
    for (int i = 0; i < m.count; ++i) EXPECT_LT(m.points[i].separation, -0.5);
  }
}

TEST(NarrowphaseFaceClip, SquareWithinKeepsItsCorners) {
  ClipPolygon polygon;
  const Vec3 corners[4] = {Vec3(0.3, 0.3, 1), Vec3(-0.3, 0.3, 1), Vec3(-0.3, -0.3, 1),
                           Vec3(0.3, -0.3, 1)};
  for (int i = 0; i < 4; ++i) {
    ClipVertex& v = polygon.vertices[polygon.count++];
    v.x = corners[i];
    v.edges = {{static_cast<std::int8_t>((i + 3) % 4), static_cast<std::int8_t>(i)}};
    v.code = i;
  }
  ClipPolygon clipped = polygon;
  clipToFaceSides(Vec3(0.5, 0.5, 1.0), 2, clipped);
  ASSERT_EQ(clipped.count, 4);
  for (int i = 0; i < 4; ++i) {
    EXPECT_TRUE(clipped.vertices[i].x.isApprox(corners[i]));
    EXPECT_EQ(clipped.vertices[i].code, static_cast<std::uint32_t>(i));
  }
  // Moved over the reference face's corner: one corner kept, two cut edges, and the reference
  // face's own corner.
  for (int i = 0; i < 4; ++i) polygon.vertices[i].x += Vec3(0.5, 0.5, 0.0);
  clipToFaceSides(Vec3(0.5, 0.5, 1.0), 2, polygon);
  ASSERT_EQ(polygon.count, 4);
  std::set<std::uint32_t> kinds;
  for (int i = 0; i < 4; ++i) {
    const std::uint32_t code = polygon.vertices[i].code;
    kinds.insert(code < 4 ? 0 : code < 20 ? 1 : 2);
    EXPECT_LE(polygon.vertices[i].x.x(), 0.5);
    EXPECT_LE(polygon.vertices[i].x.y(), 0.5);
    if (code >= 20) {
      EXPECT_TRUE(polygon.vertices[i].x.isApprox(Vec3(0.5, 0.5, 1.0)));
    }
    if (code == 2) {
      EXPECT_TRUE(polygon.vertices[i].x.isApprox(Vec3(0.2, 0.2, 1.0)));
    }
  }
  EXPECT_EQ(kinds, (std::set<std::uint32_t>{0, 1, 2}));
}

TEST(NarrowphasePointReduction, KeepsTheDeepestAndTheWidestSpread) {
  // Eight points on a circle, the third deepest.
  std::array<ManifoldPoint, 8> candidates;
  for (int i = 0; i < 8; ++i) {
    const Real angle = i * M_PI / 4;
    candidates[i] = {Vec3(std::cos(angle), std::sin(angle), 0), i == 2 ? -0.2 : -0.1,
                     static_cast<std::uint32_t>(i)};
  }
  Manifold m;
  addReducedPoints(candidates.data(), 8, Vec3::UnitZ(), 0.01, m);
  ASSERT_EQ(m.count, 4);
  EXPECT_EQ(m.points[0].id, 2u);
  EXPECT_EQ(m.points[1].id, 6u);  // opposite
  // Then the farthest from that diameter on each side: a square.
  EXPECT_EQ(sortedIds(m), (std::vector<std::uint32_t>{0, 2, 4, 6}));
}

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
