// The body shape kinds' traits: mass properties against closed forms (and the capsule's against a
// brute-force integration), bounding boxes of turned shapes, ray casts, validation and drawing.
#include "mass_aggregate_sim/engine/bodies/body_shapes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "mass_aggregate_sim/engine/bodies/mass_properties.h"
#include "mass_aggregate_sim/engine/world/world.h"

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

BodyShapeSpec partAt(const AnyBodyShape& geometry, const Vec3& position, const Real density,
                     const Quat& rotation = Quat::Identity()) {
  BodyShapeSpec shape;
  shape.geometry = geometry;
  shape.local.position = position;
  shape.local.rotation = rotation;
  shape.density = density;
  return shape;
}

// A box's inertia about its centre in its own axes: m (b^2 + c^2) / 12 and so on, full extents.
Vec3 boxInertia(const Real m, const Vec3& full) {
  return m / 12.0 *
         Vec3(full.y() * full.y() + full.z() * full.z(), full.z() * full.z() + full.x() * full.x(),
              full.x() * full.x() + full.y() * full.y());
}

// Steiner's term for a part of mass m whose centre is d from the compound's:
// m (|d|^2 E - d d^T).
Mat3 parallelAxis(const Real m, const Vec3& d) {
  return m * (d.squaredNorm() * Mat3::Identity() - d * d.transpose());
}

TEST(BodyShapeMass, TwoBoxesFollowTheParallelAxisTheorem) {
  // Two unit cubes of 1000 kg/m^3 at x = -1 and x = +1: M = 2000 kg, centre at the origin,
  // each cube m (1 + 1) / 12 = 166.67 kg m^2 about its own centre on every axis, plus
  // m d^2 = 1000 kg m^2 about y and z (d = 1 m along x):
  // I = diag(1000/3, 7000/3, 7000/3), axes the body's own (the tensor is diagonal).
  const Result<MassProperties> computed =
      computeMassProperties({partAt(BoxShape{Vec3::Constant(0.5)}, Vec3(-1.0, 0.0, 0.0), 1000.0),
                             partAt(BoxShape{Vec3::Constant(0.5)}, Vec3(1.0, 0.0, 0.0), 1000.0)},
                            0.0);
  ASSERT_TRUE(computed);
  const MassProperties& props = *computed;
  EXPECT_NEAR(props.mass, 2000.0, 1e-9);
  EXPECT_NEAR(props.volume, 2.0, 1e-12);
  EXPECT_LT(props.frame.position.norm(), 1e-12);
  EXPECT_TRUE(props.principal_inertia.isApprox(Vec3(1000.0, 7000.0, 7000.0) / 3.0, 1e-12))
      << props.principal_inertia.transpose();
  EXPECT_LT(props.frame.rotation.angularDistance(Quat::Identity()), 1e-12);
  // The same shapes with a given mass of 10 kg: the same centre, the inertia scaled by 10 / 2000.
  const Result<MassProperties> given_mass =
      computeMassProperties({partAt(BoxShape{Vec3::Constant(0.5)}, Vec3(-1.0, 0.0, 0.0), 1000.0),
                             partAt(BoxShape{Vec3::Constant(0.5)}, Vec3(1.0, 0.0, 0.0), 1000.0)},
                            10.0);
  ASSERT_TRUE(given_mass);
  const MassProperties& given = *given_mass;
  EXPECT_NEAR(given.mass, 10.0, 1e-12);
  EXPECT_TRUE(given.principal_inertia.isApprox(Vec3(1.0, 7.0, 7.0) * 10.0 / 6.0, 1e-12));
}

TEST(BodyShapeMass, AnAsymmetricBoxAndSphereCompoundHasThePrincipalAxesOfItsTensor) {
  // A 1 x 0.5 x 0.2 m box (1000 kg/m^3: m1 = 100 kg) at c1 = (0.2, -0.1, 0.3) turned 30 degrees
  // about z, and a ball of radius 0.2 m (500 kg/m^3: m2 = 500 4/3 pi 0.2^3 = 16.755 kg) at
  // c2 = (-0.6, 0.4, -0.2). Closed form: M = m1 + m2, c = (m1 c1 + m2 c2) / M,
  //   I = R diag(I_box) R^T + 2/5 m2 r^2 E + sum_k m_k (|d_k|^2 E - d_k d_k^T),  d_k = c_k - c,
  // with every off-diagonal term non-zero. Its principal moments are the roots of
  // det(I - lambda E) = 0, so they must match its invariants: trace = l1 + l2 + l3, the sum of
  // its 2x2 principal minors = l1 l2 + l2 l3 + l3 l1, det = l1 l2 l3. The mass frame's rotation
  // R_p must be a rotation with I = R_p diag(l) R_p^T, each column an eigenvector.
  const Real r = 0.2;
  const Vec3 full(1.0, 0.5, 0.2);
  const Vec3 c1(0.2, -0.1, 0.3);
  const Vec3 c2(-0.6, 0.4, -0.2);
  const Quat turn(Eigen::AngleAxisd(M_PI / 6.0, Vec3::UnitZ()));
  const Result<MassProperties> computed = computeMassProperties(
      {partAt(BoxShape{0.5 * full}, c1, 1000.0, turn), partAt(SphereShape{r}, c2, 500.0)}, 0.0);
  ASSERT_TRUE(computed);
  const MassProperties& props = *computed;
  const Real m1 = 1000.0 * full.prod();
  const Real m2 = 500.0 * 4.0 / 3.0 * M_PI * r * r * r;
  const Real m = m1 + m2;
  const Vec3 c = (m1 * c1 + m2 * c2) / m;
  const Real cos30 = std::sqrt(3.0) / 2.0;
  Mat3 rz;
  rz << cos30, -0.5, 0.0, 0.5, cos30, 0.0, 0.0, 0.0, 1.0;
  const Mat3 inertia = rz * boxInertia(m1, full).asDiagonal() * rz.transpose() +
                       0.4 * m2 * r * r * Mat3::Identity() + parallelAxis(m1, c1 - c) +
                       parallelAxis(m2, c2 - c);
  EXPECT_NEAR(props.mass, m, 1e-12 * m);
  EXPECT_LT((props.frame.position - c).norm(), 1e-12);
  for (int i = 0; i < 3; ++i) {
    for (int j = i + 1; j < 3; ++j) EXPECT_GT(std::abs(inertia(i, j)), 0.1) << i << j;
  }
  const Vec3 l = props.principal_inertia;
  const Real scale = inertia.trace();
  const Real minors = inertia(0, 0) * inertia(1, 1) - inertia(0, 1) * inertia(1, 0) +
                      inertia(1, 1) * inertia(2, 2) - inertia(1, 2) * inertia(2, 1) +
                      inertia(2, 2) * inertia(0, 0) - inertia(2, 0) * inertia(0, 2);
  EXPECT_NEAR(l.sum(), inertia.trace(), 1e-12 * scale);
  EXPECT_NEAR(l.x() * l.y() + l.y() * l.z() + l.z() * l.x(), minors, 1e-12 * scale * scale);
  EXPECT_NEAR(l.prod(), inertia.determinant(), 1e-12 * scale * scale * scale);
  const Mat3 axes = props.frame.rotation.toRotationMatrix();
  EXPECT_NEAR(axes.determinant(), 1.0, 1e-12);
  EXPECT_LT((axes * l.asDiagonal() * axes.transpose() - inertia).norm(), 1e-12 * scale);
  for (int k = 0; k < 3; ++k) {
    EXPECT_LT((inertia * axes.col(k) - l[k] * axes.col(k)).norm(), 1e-12 * scale) << k;
  }
  std::printf("[ compound ] m %.4f kg, c (%.5f, %.5f, %.5f), principal (%.5f, %.5f, %.5f) kg m^2\n",
              props.mass, c.x(), c.y(), c.z(), l.x(), l.y(), l.z());
  // As a body in a world at a pose: its centre of mass and axes carried by the pose, its
  // moments and mass as computed.
  World world;
  BodySpec spec;
  spec.shapes = {partAt(BoxShape{0.5 * full}, c1, 1000.0, turn), partAt(SphereShape{r}, c2, 500.0)};
  spec.pose.position = Vec3(1.0, 2.0, 3.0);
  spec.pose.rotation = Quat(Eigen::AngleAxisd(0.4, Vec3(1.0, -2.0, 0.5).normalized()));
  const BodyId id = *world.addBody(spec);
  const std::size_t i = *world.bodies().find(id);
  EXPECT_NEAR(world.bodies().mass(i), m, 1e-12 * m);
  EXPECT_LT((world.bodies().position(i) - spec.pose.apply(c)).norm(), 1e-12);
  EXPECT_TRUE(world.bodies().principalInertia(i).isApprox(l, 1e-12));
  const Mat3 world_axes = world.bodies().orientation(i).toRotationMatrix();
  const Mat3 pose_r = spec.pose.rotation.toRotationMatrix();
  EXPECT_LT(
      (world_axes * l.asDiagonal() * world_axes.transpose() - pose_r * inertia * pose_r.transpose())
          .norm(),
      1e-12 * scale);
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
