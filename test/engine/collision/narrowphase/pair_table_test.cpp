// The dispatch: every ordered pair of BodyShapeKinds has a pair function, the reversed order
// flips the normal and keeps the points, and the completeness check rejects a kind without one.
#include "manifold_checks.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

using namespace narrowphase_test;  // NOLINT

struct Blob {};  // a kind nobody wrote pair functions for
static_assert(!narrowphase_detail::coversEveryPair(KindList<SphereShape, Blob>{}));
static_assert(!narrowphase_detail::coversEveryPlane(KindList<SphereShape, Blob>{}));
static_assert(narrowphase_detail::kCovered<BoxShape, SphereShape>);
static_assert(!narrowphase_detail::HasPairFunction<BoxShape, SphereShape>::value);

SphereShape sample(KindTag<SphereShape>) { return SphereShape{0.5}; }
BoxShape sample(KindTag<BoxShape>) { return BoxShape{Vec3(0.5, 0.4, 0.3)}; }
CapsuleShape sample(KindTag<CapsuleShape>) { return CapsuleShape{0.3, 0.5}; }

TEST(NarrowphasePairTable, ReversedOrderFlipsTheNormalAndKeepsThePoints) {
  const Frame fa = frameAt(Vec3(0.1, -0.2, 0.0), about(Vec3(1, 0, 1), 0.3));
  const Frame fb = frameAt(Vec3(0.3, 0.1, 0.65), about(Vec3(0, 1, 2), 0.7));
  int pairs = 0;
  forEachKind(BodyShapeKinds{}, [&](auto tag_a) {
    forEachKind(BodyShapeKinds{}, [&](auto tag_b) {
      const auto a = sample(tag_a);
      const auto b = sample(tag_b);
      const Manifold forward = collideShapes(a, fa, b, fb, 0.0);
      const Manifold backward = collideShapes(b, fb, a, fa, 0.0);
      SCOPED_TRACE(std::string(BodyShapeKind<typename decltype(tag_a)::type>::kName) + " " +
                   BodyShapeKind<typename decltype(tag_b)::type>::kName);
      ASSERT_GE(forward.count, 1);
      ASSERT_TRUE(finiteUnitNormal(forward));
      expectNormal(backward, -forward.normal);
      std::vector<Expected> expected;
      for (int i = 0; i < forward.count; ++i) {
        expected.push_back({forward.points[i].point, forward.points[i].separation});
      }
      expectPoints(backward, expected);
      ++pairs;
    });
  });
  EXPECT_EQ(pairs, 9);
}

TEST(NarrowphasePairTable, SwappedCallIsTheWrittenOneFlipped) {
  const SphereShape sphere{0.5};
  const BoxShape box{Vec3(1.0, 0.5, 0.25)};
  const Frame fs = frameAt(Vec3(0.3, 0.2, 0.6));
  const Frame fb = frameAt(Vec3::Zero(), about(Vec3::UnitZ(), 0.2));
  const Manifold written = collide(sphere, fs, box, fb, 0.0);
  const Manifold swapped = collideShapes(box, fb, sphere, fs, 0.0);
  ASSERT_EQ(written.count, 1);
  ASSERT_EQ(swapped.count, 1);
  EXPECT_EQ(swapped.normal, -written.normal);
  EXPECT_EQ(swapped.points[0].point, written.points[0].point);
  EXPECT_EQ(swapped.points[0].separation, written.points[0].separation);
  EXPECT_EQ(swapped.points[0].id, written.points[0].id);
}

TEST(NarrowphasePairTable, CoincidentShapesGiveNoNaN) {
  const Frame f = frameAt(Vec3(1, 2, 3), about(Vec3(1, 1, 0), 0.4));
  forEachKind(BodyShapeKinds{}, [&](auto tag_a) {
    forEachKind(BodyShapeKinds{}, [&](auto tag_b) {
      const Manifold m = collideShapes(sample(tag_a), f, sample(tag_b), f, 0.0);
      EXPECT_TRUE(finiteUnitNormal(m));
      EXPECT_GE(m.count, 1);
    });
    const Manifold plane = collideWithPlaneShape(sample(tag_a), f, Vec3::UnitZ(), 3.0, 0.0);
    EXPECT_TRUE(finiteUnitNormal(plane));
    EXPECT_GE(plane.count, 1);
  });
  const CapsuleShape dot{0.3, 0.0};
  forEachKind(BodyShapeKinds{}, [&](auto tag) {
    const Manifold m = collideShapes(dot, f, sample(tag), f, 0.0);
    EXPECT_TRUE(finiteUnitNormal(m));
    EXPECT_GE(m.count, 1);
  });
}

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
