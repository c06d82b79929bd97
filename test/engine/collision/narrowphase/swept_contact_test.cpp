// The swept contact (swept_contact.h): a fast pair's speculative contact is made where the shapes
// touch, or on the way past when they pass each other, and none when they move apart; a pair
// that cannot close its gap within the step keeps collideAny's.
#include "engine/collision/narrowphase/swept_contact.h"

#include "engine/collision/narrowphase/any_shape.h"
#include "manifold_checks.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

using namespace narrowphase_test;  // NOLINT

constexpr Real kDt = 1.0 / 60.0;
constexpr Real kRadius = 0.03;
constexpr Real kSpeed = 11.0;  // a ball after a 6 m fall
// The margin findBodyContacts gives a ball falling at kSpeed beside one at rest
// (BodySettings::speculative_distance plus its travel).
constexpr Real kMargin = 0.02 + kSpeed * kDt;

const AnyBodyShape kBall = SphereShape{kRadius};

// A ball falling at `speed` from `start` onto one at rest at the origin; neither turns.
Manifold ballFallingOnBall(const Vec3& start, const Real speed = kSpeed) {
  const Frame resting = frameAt(Vec3::Zero());
  const Frame falling = frameAt(start);
  return sweptContact(SweptShape{kBall, resting, Vec3::Zero()},
                      SweptShape{kBall, falling, Vec3(0.0, 0.0, -speed)}, kMargin, kDt);
}

TEST(SweptContact, ABallFallingPastAnotherGetsAContactItsFallDoesNotClose) {
  // 7 cm beside it, 15 cm above: the centres pass 7 cm apart, level, at t = 0.15 / kSpeed.
  const Vec3 start(0.07, 0.0, 0.15);
  const Manifold at_start =
      collideAny(kBall, frameAt(Vec3::Zero()), kBall, frameAt(start), kMargin);
  ASSERT_EQ(at_start.count, 1);  // what the start alone gives: a plane across the fall
  EXPECT_GT(at_start.normal.z(), 0.9);
  const Manifold m = ballFallingOnBall(start);
  ASSERT_EQ(m.count, 1);
  // Made on the way past, where the rest of the step's fall no longer closes it: its gap, taken
  // back along its normal, s + (v_b - v_a).n t, is open over the whole step, and its plane is
  // nearly the level one they pass across.
  const Real opens = Vec3(0.0, 0.0, -kSpeed).dot(m.normal);
  EXPECT_GE(m.points[0].separation, 0.01);
  EXPECT_GE(m.points[0].separation + opens * kDt, 0.0);
  EXPECT_LT(m.normal.z(), 0.25);
  EXPECT_GT(m.normal.x(), 0.95);
}

TEST(SweptContact, ABallFallingOnAnotherObliquelyGetsTheNormalItTouchesAlong) {
  // Touching at 45 degrees: centres 6 cm apart along (1, 0, 1) / sqrt(2).
  const Real side = 2.0 * kRadius * std::sqrt(0.5);
  const Real drop = 0.12;  // how far it falls before touching
  const Manifold m = ballFallingOnBall(Vec3(side, 0.0, side + drop));
  ASSERT_EQ(m.count, 1);
  const Vec3 normal = Vec3(1.0, 0.0, 1.0).normalized();
  expectNormal(m, normal, 5e-3);
  // It closes along the normal at kSpeed cos 45 for drop / kSpeed: a gap of drop cos 45.
  EXPECT_NEAR(m.points[0].separation, drop * std::sqrt(0.5), 1e-4);
  // The touch point, taken back by half the falling ball's move.
  EXPECT_TRUE((m.points[0].point - (kRadius * normal + Vec3(0.0, 0.0, 0.5 * drop))).norm() < 1e-3)
      << m.points[0].point.transpose();
}

TEST(SweptContact, APairThatCannotCloseItsGapInTheStepKeepsCollideAnysContact) {
  const Vec3 start(0.01, 0.0, 0.07);  // 1.07 cm apart, falling 0.83 cm in the step
  const Manifold m = ballFallingOnBall(start, 0.5);
  const Manifold at_start =
      collideAny(kBall, frameAt(Vec3::Zero()), kBall, frameAt(start), kMargin);
  ASSERT_EQ(m.count, 1);
  EXPECT_EQ(m.normal, at_start.normal);
  EXPECT_EQ(m.points[0].point, at_start.points[0].point);
  EXPECT_EQ(m.points[0].separation, at_start.points[0].separation);
}

TEST(SweptContact, AHeadOnPairWithinTheMarginKeepsItsWholeGap) {
  // 19 cm apart, closing 18.3 cm in the step: it cannot touch this step; its contact keeps the
  // whole gap, which the solver will not let close faster than it can.
  const Manifold m = ballFallingOnBall(Vec3(0.0, 0.0, 2.0 * kRadius + 0.19));
  ASSERT_EQ(m.count, 1);
  expectNormal(m, Vec3::UnitZ(), 1e-12);
  EXPECT_NEAR(m.points[0].separation, 0.19, 1e-12);
}

TEST(SweptContact, APairMovingApartFasterThanItsGapGetsNone) {
  const Frame resting = frameAt(Vec3::Zero());
  const Frame rising = frameAt(Vec3(0.0, 0.0, 0.15));
  ASSERT_EQ(collideAny(kBall, resting, kBall, rising, kMargin).count, 1);
  const Manifold m = sweptContact(SweptShape{kBall, resting, Vec3::Zero()},
                                  SweptShape{kBall, rising, Vec3(0.0, 0.0, kSpeed)}, kMargin, kDt);
  EXPECT_EQ(m.count, 0);
}

TEST(SweptContact, ABoxFallingFlatOnABoxTouchesWithItsFourCorners) {
  const AnyBodyShape cube = BoxShape{Vec3(0.5, 0.5, 0.5)};
  const Frame below = frameAt(Vec3::Zero());
  const Frame above = frameAt(Vec3(0.2, 0.1, 1.1), about(Vec3::UnitZ(), 0.3));
  const Manifold m =
      sweptContact(SweptShape{cube, below, Vec3::Zero()},
                   SweptShape{cube, above, Vec3(0.0, 0.0, -10.0)}, 0.02 + 10.0 * kDt, kDt);
  ASSERT_EQ(m.count, 4);
  expectNormal(m, Vec3::UnitZ(), 1e-12);
  for (int k = 0; k < m.count; ++k) EXPECT_NEAR(m.points[k].separation, 0.1, 1e-12);
}

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
