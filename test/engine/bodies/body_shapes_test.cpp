// The body shape kinds' traits: mass properties against closed forms (and the capsule's against a
// brute-force integration), bounding boxes of turned shapes, ray casts, validation and drawing.
#include "mass_aggregate_sim/engine/bodies/body_shapes.h"

#include <gtest/gtest.h>

#include <cmath>

namespace mass_aggregate_sim {
namespace engine {
namespace {

using Sphere = BodyShapeKind<SphereShape>;
using Box = BodyShapeKind<BoxShape>;
using Capsule = BodyShapeKind<CapsuleShape>;

Frame frameAt(const Vec3& position, const Vec3& axis = Vec3::UnitZ(), const Real angle = 0.0) {
  return Frame(Transform{position, Quat(Eigen::AngleAxisd(angle, axis.normalized()))});
}

void expectAabb(const Aabb& box, const Vec3& lower, const Vec3& upper) {
  EXPECT_TRUE(box.lower.isApprox(lower, 1e-12)) << box.lower.transpose();
  EXPECT_TRUE(box.upper.isApprox(upper, 1e-12)) << box.upper.transpose();
}

void expectHit(const std::optional<RayShapeHit>& hit, const Real t, const Vec3& normal) {
  ASSERT_TRUE(hit.has_value());
  EXPECT_NEAR(hit->t, t, 1e-12);
  EXPECT_TRUE(hit->normal.isApprox(normal, 1e-12)) << hit->normal.transpose();
}

TEST(BodyShapeMass, SphereMatchesClosedForm) {
  const SphereShape sphere{0.7};
  const Real volume = 4.0 / 3.0 * M_PI * 0.343;
  EXPECT_NEAR(Sphere::volume(sphere), volume, 1e-14);
  EXPECT_TRUE(Sphere::unitInertia(sphere).isApprox(Vec3::Constant(0.4 * volume * 0.49), 1e-14));
}

TEST(BodyShapeMass, BoxMatchesClosedForm) {
  // Full extents 1 x 2 x 3: m = 6, I = m (b^2 + c^2) / 12 and so on.
  const BoxShape box{Vec3(0.5, 1.0, 1.5)};
  EXPECT_NEAR(Box::volume(box), 6.0, 1e-14);
  EXPECT_TRUE(Box::unitInertia(box).isApprox(Vec3(6.5, 5.0, 2.5), 1e-14))
      << Box::unitInertia(box).transpose();
}

TEST(BodyShapeMass, CapsuleMatchesClosedFormAndGridIntegration) {
  const CapsuleShape capsule{0.5, 0.6};
  const Real r = 0.5;
  const Real h = 0.6;
  EXPECT_NEAR(Capsule::volume(capsule), M_PI * r * r * 2.0 * h + 4.0 / 3.0 * M_PI * r * r * r,
              1e-14);
  // Brute force: the midpoint rule over one octant of the bounding box (the capsule is symmetric
  // in all three planes), counting cells whose centre is inside.
  const int n = 300;
  const Vec3 extent(r, r, h + r);
  const Vec3 cell = extent / n;
  const Real cell_volume = cell.prod();
  Real volume = 0.0;
  Vec3 second_moments = Vec3::Zero();  // integrals of x^2, y^2, z^2
  for (int i = 0; i < n; ++i) {
    const Real x = (i + 0.5) * cell.x();
    for (int j = 0; j < n; ++j) {
      const Real y = (j + 0.5) * cell.y();
      const Real across = x * x + y * y;
      if (across > r * r) continue;
      for (int k = 0; k < n; ++k) {
        const Real z = (k + 0.5) * cell.z();
        const Real beyond = std::max(z - h, 0.0);
        if (across + beyond * beyond > r * r) continue;
        volume += cell_volume;
        second_moments += cell_volume * Vec3(x * x, y * y, z * z);
      }
    }
  }
  volume *= 8.0;
  second_moments *= 8.0;
  const Vec3 grid_inertia(second_moments.y() + second_moments.z(),
                          second_moments.z() + second_moments.x(),
                          second_moments.x() + second_moments.y());
  EXPECT_NEAR(Capsule::volume(capsule), volume, 2e-4 * volume);
  const Vec3 inertia = Capsule::unitInertia(capsule);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(inertia[k], grid_inertia[k], 5e-4 * grid_inertia[k]);
  // Closed form by another route: a ball of radius r split at its equator, halves moved to +-h.
  const Real ball = 4.0 / 3.0 * M_PI * r * r * r;
  const Real cylinder = M_PI * r * r * 2.0 * h;
  EXPECT_NEAR(inertia.z(), 0.4 * ball * r * r + 0.5 * cylinder * r * r, 1e-14);
}

TEST(BodyShapeMass, CapsuleWithoutLengthIsASphere) {
  // Just above the validation's limit, the capsule's properties approach the sphere's.
  const CapsuleShape capsule{0.3, 1e-12};
  const SphereShape sphere{0.3};
  EXPECT_NEAR(Capsule::volume(capsule), Sphere::volume(sphere), 1e-12);
  EXPECT_TRUE(Capsule::unitInertia(capsule).isApprox(Sphere::unitInertia(sphere), 1e-9));
}

TEST(BodyShapeAabb, TurnedShapes) {
  expectAabb(Sphere::aabb(SphereShape{0.5}, frameAt(Vec3(1, 2, 3), Vec3::UnitX(), 0.7)),
             Vec3(0.5, 1.5, 2.5), Vec3(1.5, 2.5, 3.5));
  const BoxShape box{Vec3(1.0, 2.0, 3.0)};
  expectAabb(Box::aabb(box, frameAt(Vec3(1, 0, 0), Vec3::UnitZ(), M_PI / 2)), Vec3(-1, -1, -3),
             Vec3(3, 1, 3));
  const Real s = std::sqrt(0.5);
  expectAabb(Box::aabb(box, frameAt(Vec3::Zero(), Vec3::UnitZ(), M_PI / 4)), -Vec3(3 * s, 3 * s, 3),
             Vec3(3 * s, 3 * s, 3));
  const CapsuleShape capsule{0.5, 1.0};
  expectAabb(Capsule::aabb(capsule, frameAt(Vec3::Zero(), Vec3::UnitY(), M_PI / 2)),
             Vec3(-1.5, -0.5, -0.5), Vec3(1.5, 0.5, 0.5));
  expectAabb(Capsule::aabb(capsule, frameAt(Vec3(0, 0, 1), Vec3::UnitY(), M_PI / 4)),
             Vec3(-s - 0.5, -0.5, 1 - s - 0.5), Vec3(s + 0.5, 0.5, 1 + s + 0.5));
}

TEST(BodyShapeRaycast, SphereFirstEntryNoneFromInsideOrBeyondReach) {
  const SphereShape sphere{0.5};
  const Frame frame = frameAt(Vec3(1, 2, 3));
  expectHit(Sphere::raycast(sphere, frame, Vec3(1, 2, 10), -Vec3::UnitZ(), 100.0), 6.5,
            Vec3::UnitZ());
  EXPECT_FALSE(Sphere::raycast(sphere, frame, Vec3(1, 2, 3.2), Vec3::UnitZ(), 100.0));
  EXPECT_FALSE(Sphere::raycast(sphere, frame, Vec3(1, 2, 10), -Vec3::UnitZ(), 6.0));
  EXPECT_FALSE(Sphere::raycast(sphere, frame, Vec3(1, 2, 10), Vec3::UnitZ(), 100.0));
}

TEST(BodyShapeRaycast, TurnedBox) {
  // Turned a quarter about z: its local y (half extent 2) lies along world x.
  const BoxShape box{Vec3(1.0, 2.0, 3.0)};
  const Frame frame = frameAt(Vec3(5, 0, 0), Vec3::UnitZ(), M_PI / 2);
  expectHit(Box::raycast(box, frame, Vec3::Zero(), Vec3::UnitX(), 100.0), 3.0, -Vec3::UnitX());
  expectHit(Box::raycast(box, frame, Vec3(5.5, 10, 0), -Vec3::UnitY(), 100.0), 9.0, Vec3::UnitY());
  EXPECT_FALSE(Box::raycast(box, frame, Vec3(5, 0, 0), Vec3::UnitX(), 100.0));
  EXPECT_FALSE(Box::raycast(box, frame, Vec3(0, 1.5, 0), Vec3::UnitX(), 100.0));
  EXPECT_FALSE(Box::raycast(box, frame, Vec3::Zero(), Vec3::UnitX(), 2.5));
}

TEST(BodyShapeRaycast, TurnedCapsuleCapAndSide) {
  // Lying along world x, ends at x = +-1.
  const CapsuleShape capsule{0.5, 1.0};
  const Frame frame = frameAt(Vec3::Zero(), Vec3::UnitY(), M_PI / 2);
  expectHit(Capsule::raycast(capsule, frame, Vec3(5, 0, 0), -Vec3::UnitX(), 100.0), 3.5,
            Vec3::UnitX());
  expectHit(Capsule::raycast(capsule, frame, Vec3(0.7, 0, 5), -Vec3::UnitZ(), 100.0), 4.5,
            Vec3::UnitZ());
  EXPECT_FALSE(Capsule::raycast(capsule, frame, Vec3(1.2, 0, 0), Vec3::UnitX(), 100.0));
  EXPECT_FALSE(Capsule::raycast(capsule, frame, Vec3(0, 0, 5), Vec3::UnitX(), 100.0));
}

TEST(BodyShapeValidate, RefusesNonPositiveAndNonFinite) {
  EXPECT_TRUE(Sphere::validate(SphereShape{0.1}));
  EXPECT_TRUE(Box::validate(BoxShape{Vec3(0.1, 0.2, 0.3)}));
  EXPECT_TRUE(Capsule::validate(CapsuleShape{0.1, 0.2}));
  for (const Real bad : {0.0, -1.0, std::nan(""), HUGE_VAL}) {
    const Status sphere = Sphere::validate(SphereShape{bad});
    EXPECT_FALSE(sphere);
    EXPECT_EQ(sphere.message(), "sphere radius must be finite and > 0");
    const Status box = Box::validate(BoxShape{Vec3(0.1, bad, 0.3)});
    EXPECT_FALSE(box);
    EXPECT_EQ(box.message(), "box half_extents must be finite and > 0");
    EXPECT_EQ(Capsule::validate(CapsuleShape{bad, 0.2}).message(),
              "capsule radius must be finite and > 0");
    EXPECT_EQ(Capsule::validate(CapsuleShape{0.1, bad}).message(),
              "capsule half_length must be finite and > 0");
  }
}

TEST(BodyShapeDescribe, PartsInTheShapesFrame) {
  const std::vector<ShapePrimitive> ball = Sphere::describe(SphereShape{0.5});
  ASSERT_EQ(ball.size(), 1u);
  EXPECT_EQ(ball[0].type, ShapePrimitive::Type::kSphere);
  EXPECT_TRUE(ball[0].size.isApprox(Vec3::Ones()));
  const std::vector<ShapePrimitive> cube = Box::describe(BoxShape{Vec3(1, 2, 3)});
  ASSERT_EQ(cube.size(), 1u);
  EXPECT_EQ(cube[0].type, ShapePrimitive::Type::kBox);
  EXPECT_TRUE(cube[0].size.isApprox(Vec3(2, 4, 6)));
  const std::vector<ShapePrimitive> capsule = Capsule::describe(CapsuleShape{0.25, 1.0});
  ASSERT_EQ(capsule.size(), 3u);
  EXPECT_EQ(capsule[0].type, ShapePrimitive::Type::kCylinder);
  EXPECT_TRUE(capsule[0].center.isZero());
  EXPECT_TRUE(capsule[0].size.isApprox(Vec3(0.5, 0.5, 2.0)));
  for (int end = 0; end < 2; ++end) {
    EXPECT_EQ(capsule[1 + end].type, ShapePrimitive::Type::kSphere);
    EXPECT_TRUE(capsule[1 + end].size.isApprox(Vec3::Constant(0.5)));
    EXPECT_TRUE(capsule[1 + end].center.isApprox(Vec3(0, 0, end == 0 ? -1.0 : 1.0)));
  }
}

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
