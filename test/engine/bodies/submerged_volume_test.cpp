// The part of each body shape below a liquid surface (BodyShapeKind::submerged), against closed
// forms, against the rest of the shape above the surface, and against a count of grid points.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "mass_aggregate_sim/engine/bodies/body_shapes.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

constexpr Real kPi = 3.14159265358979323846;

Frame placed(const Vec3& position, const Quat& q = Quat::Identity()) {
  return Frame(Transform{position, q});
}

template <typename Shape>
SubmergedVolume below(const Shape& shape, const Frame& frame, const Vec3& up, const Real height) {
  return BodyShapeKind<Shape>::submerged(shape, frame, LiquidSurface{up, height});
}

// The part below up.x = height and the part below -up.x = -height (the rest) make the shape.
template <typename Shape>
void expectPartsMakeTheWhole(const Shape& shape, const Frame& frame, const Vec3& up,
                             const Real height, const Real tolerance) {
  const SubmergedVolume under = below(shape, frame, up, height);
  const SubmergedVolume over = below(shape, frame, Vec3(-up), -height);
  const Real whole = BodyShapeKind<Shape>::volume(shape);
  EXPECT_NEAR(under.volume + over.volume, whole, tolerance * whole);
  EXPECT_NEAR((under.moment + over.moment - whole * frame.position).norm(), 0.0,
              tolerance * whole * (1.0 + frame.position.norm()));
}

// Volume and centroid of {x inside, up.x < height} by the midpoint rule on an n^3 grid over the
// box centre +- reach.
SubmergedVolume countedBelow(const std::function<bool(const Vec3&)>& inside, const Vec3& centre,
                             const Real reach, const Vec3& up, const Real height, const int n) {
  const Real cell = 2.0 * reach / n;
  SubmergedVolume sum;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      for (int k = 0; k < n; ++k) {
        const Vec3 x = centre + Vec3(-reach + (i + 0.5) * cell, -reach + (j + 0.5) * cell,
                                     -reach + (k + 0.5) * cell);
        if (up.dot(x) < height && inside(x)) {
          sum.volume += cell * cell * cell;
          sum.moment += cell * cell * cell * x;
        }
      }
    }
  }
  return sum;
}

void expectClose(const SubmergedVolume& exact, const SubmergedVolume& counted, const Real whole,
                 const Real length) {
  EXPECT_NEAR(exact.volume, counted.volume, 2e-3 * whole);
  ASSERT_GT(exact.volume, 0.0);
  EXPECT_NEAR((exact.moment / exact.volume - counted.moment / counted.volume).norm(), 0.0,
              3e-3 * length);
}

TEST(SubmergedVolume, ABallsCapHasTheClosedFormVolumeAndCentroid) {
  const SphereShape ball{0.5};
  const Real r = ball.radius;
  const Vec3 c(1.0, -2.0, 3.0);
  const Frame frame = placed(c);
  EXPECT_EQ(below(ball, frame, Vec3::UnitZ(), c.z() - r).volume, 0.0);
  const SubmergedVolume whole = below(ball, frame, Vec3::UnitZ(), c.z() + r + 1e-9);
  EXPECT_NEAR(whole.volume, 4.0 / 3.0 * kPi * r * r * r, 1e-15);
  EXPECT_NEAR((whole.moment / whole.volume - c).norm(), 0.0, 1e-12);
  // The lower half: 2/3 pi r^3, its centroid 3r/8 below the centre.
  const SubmergedVolume half = below(ball, frame, Vec3::UnitZ(), c.z());
  EXPECT_NEAR(half.volume, 2.0 / 3.0 * kPi * r * r * r, 1e-15);
  EXPECT_NEAR((half.moment / half.volume - (c - Vec3(0.0, 0.0, 3.0 * r / 8.0))).norm(), 0.0, 1e-12);
  // A cap of height d = r / 4 along a tilted up: pi d^2 (3r - d) / 3.
  const Vec3 up = Vec3(1.0, 2.0, 2.0) / 3.0;
  const Real d = 0.25 * r;
  const SubmergedVolume cap = below(ball, frame, up, up.dot(c) - r + d);
  EXPECT_NEAR(cap.volume, kPi * d * d * (3.0 * r - d) / 3.0, 1e-15);
  for (const Real height : {-0.4, -0.1, 0.0, 0.2, 0.45}) {
    expectPartsMakeTheWhole(ball, frame, up, up.dot(c) + height, 1e-12);
  }
}

TEST(SubmergedVolume, AnUprightBoxIsCutLevel) {
  const BoxShape box{Vec3(0.5, 0.25, 0.1)};
  const Vec3 c(0.0, 0.0, 1.0);
  const Frame frame = placed(c);
  // 4 cm of its 20 cm height under water: 1.0 x 0.5 x 0.04, centroid 2 cm above its bottom.
  const SubmergedVolume part = below(box, frame, Vec3::UnitZ(), 0.94);
  EXPECT_NEAR(part.volume, 1.0 * 0.5 * 0.04, 1e-14);
  EXPECT_NEAR((part.moment / part.volume - Vec3(0.0, 0.0, 0.92)).norm(), 0.0, 1e-12);
  EXPECT_EQ(below(box, frame, Vec3::UnitZ(), 0.9).volume, 0.0);
  EXPECT_NEAR(below(box, frame, Vec3::UnitZ(), 1.1).volume, 0.1, 1e-15);
}

TEST(SubmergedVolume, ABoxOnItsEdgeAndOnItsCorner) {
  const BoxShape cube{Vec3::Constant(0.5)};
  // Turned 45 degrees about x, the surface through its centre: the lower half is a prism of
  // triangles (0, +-sqrt(2)/2, 0), (0, 0, -sqrt(2)/2) whose centroid is sqrt(2)/6 below.
  const Frame edge = placed(Vec3::Zero(), Quat(Eigen::AngleAxisd(kPi / 4.0, Vec3::UnitX())));
  const SubmergedVolume half = below(cube, edge, Vec3::UnitZ(), 0.0);
  EXPECT_NEAR(half.volume, 0.5, 1e-14);
  EXPECT_NEAR((half.moment / half.volume - Vec3(0.0, 0.0, -std::sqrt(2.0) / 6.0)).norm(), 0.0,
              1e-12);
  // Level with the diagonal up = (1, 1, 1)/sqrt(3), the corner (1, 1, 1)/2 out by a little: the
  // part above is the tetrahedron of legs a = delta sqrt(3) at that corner, a^3 / 6, its
  // centroid a/4 in from the corner along each axis.
  const Vec3 up = Vec3::Ones().normalized();
  const Real delta = 0.05;
  const Real a = delta * std::sqrt(3.0);
  const SubmergedVolume most = below(cube, placed(Vec3::Zero()), up, std::sqrt(3.0) / 2.0 - delta);
  const Real tetrahedron = a * a * a / 6.0;
  EXPECT_NEAR(most.volume, 1.0 - tetrahedron, 1e-14);
  EXPECT_NEAR((most.moment + tetrahedron * (Vec3::Constant(0.5) - 0.25 * Vec3::Constant(a))).norm(),
              0.0, 1e-14);
}

TEST(SubmergedVolume, ACapsuleUprightAndLyingHasTheClosedForms) {
  const CapsuleShape capsule{0.2, 0.6};
  const Real r = capsule.radius;
  const Real l = capsule.half_length;
  const Real cylinder = kPi * r * r * 2.0 * l;
  const Real ball = 4.0 / 3.0 * kPi * r * r * r;
  // The hemispheres' disks are integrated numerically (capsule_shape.cpp): within 1e-8.
  const Real tolerance = 1e-8 * (cylinder + ball);
  // Upright, cut at its centre: half the cylinder (centroid l/2 below) and one hemisphere
  // (l + 3r/8 below).
  const SubmergedVolume upright = below(capsule, placed(Vec3::Zero()), Vec3::UnitZ(), 0.0);
  EXPECT_NEAR(upright.volume, 0.5 * (cylinder + ball), tolerance);
  const Real upright_moment = 0.5 * cylinder * (-0.5 * l) + 0.5 * ball * (-(l + 3.0 * r / 8.0));
  EXPECT_NEAR(upright.moment.z(), upright_moment, tolerance * l);
  // Lying along x, cut along its axis: the half cylinder's centroid 4r/(3 pi) below, the half
  // ball's 3r/8.
  const Frame lying = placed(Vec3::Zero(), Quat(Eigen::AngleAxisd(kPi / 2.0, Vec3::UnitY())));
  const SubmergedVolume flat = below(capsule, lying, Vec3::UnitZ(), 0.0);
  EXPECT_NEAR(flat.volume, 0.5 * (cylinder + ball), tolerance);
  const Real flat_moment = -0.5 * cylinder * 4.0 * r / (3.0 * kPi) - 0.5 * ball * 3.0 * r / 8.0;
  EXPECT_NEAR(flat.moment.z(), flat_moment, tolerance * r);
  EXPECT_NEAR(flat.moment.x(), 0.0, tolerance * l);
  // Grazing its lowest line (the turn by pi/2 leaves the axis 2e-16 off level): a sliver, never
  // a negative volume.
  const Real grazing = below(capsule, lying, Vec3::UnitZ(), -r).volume;
  EXPECT_GE(grazing, 0.0);
  EXPECT_LT(grazing, 1e-20);
  EXPECT_NEAR(below(capsule, lying, Vec3::UnitZ(), r).volume, cylinder + ball, tolerance);
}

TEST(SubmergedVolume, TiltedShapesAgreeWithTheirRestAndWithAGridCount) {
  const Quat turn = Quat(Eigen::AngleAxisd(0.7, Vec3(0.3, -0.5, 0.8).normalized())).normalized();
  const Vec3 c(0.3, -0.2, 0.1);
  const Frame frame = placed(c, turn);
  const Vec3 up = Vec3(0.1, 0.2, 1.0).normalized();
  const BoxShape box{Vec3(0.5, 0.3, 0.15)};
  const CapsuleShape capsule{0.2, 0.4};
  const auto in_box = [&](const Vec3& x) {
    return (frame.applyInverse(x).cwiseAbs().array() <= box.half_extents.array()).all();
  };
  const auto in_capsule = [&](const Vec3& x) {
    const Vec3 local = frame.applyInverse(x);
    const Real along = std::clamp(local.z(), -capsule.half_length, capsule.half_length);
    return (local - Vec3(0.0, 0.0, along)).norm() <= capsule.radius;
  };
  for (const Real height : {-0.35, -0.12, 0.0, 0.07, 0.3}) {
    const Real level = up.dot(c) + height;
    expectPartsMakeTheWhole(box, frame, up, level, 1e-12);
    expectPartsMakeTheWhole(capsule, frame, up, level, 1e-9);
    expectClose(below(box, frame, up, level), countedBelow(in_box, c, 0.6, up, level, 160),
                BodyShapeKind<BoxShape>::volume(box), 0.6);
    expectClose(below(capsule, frame, up, level), countedBelow(in_capsule, c, 0.6, up, level, 160),
                BodyShapeKind<CapsuleShape>::volume(capsule), 0.6);
  }
}

TEST(SubmergedVolume, ACapsuleNearlyUprightIsAsExactAsUpright) {
  // The cut through each disk turns from a step (upright) to a segment: the quadrature, split
  // where the surface enters and leaves the disks, keeps the upright answer at a millionth of a
  // radian (volume and height of the centroid change by its square, 1e-12).
  const CapsuleShape capsule{0.2, 0.6};
  const Frame upright = placed(Vec3::Zero());
  const Frame nearly = placed(Vec3::Zero(), Quat(Eigen::AngleAxisd(1e-6, Vec3::UnitX())));
  for (const Real height : {-0.7, -0.3, 0.0, 0.25, 0.65}) {
    const SubmergedVolume a = below(capsule, upright, Vec3::UnitZ(), height);
    const SubmergedVolume b = below(capsule, nearly, Vec3::UnitZ(), height);
    EXPECT_NEAR(a.volume, b.volume, 1e-10) << height;
    EXPECT_NEAR(a.moment.z(), b.moment.z(), 1e-10) << height;
  }
}

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
