#include <gtest/gtest.h>

#include <cmath>

#include "engine/collision/geometry.h"
#include "mass_aggregate_sim/engine/collision/colliders.h"
#include "mass_aggregate_sim/engine/world/world.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

constexpr Real kTol = 1e-12;

void expectContact(const std::optional<ShapeContact>& contact, const Vec3& normal,
                   const Real penetration) {
  ASSERT_TRUE(contact.has_value());
  EXPECT_NEAR((contact->normal - normal).norm(), 0.0, kTol);
  EXPECT_NEAR(contact->penetration, penetration, kTol);
}

TEST(SphereVsPlane, HitsMissesAndDeepInside) {
  PlaneCollider ground;  // z < 0 is solid
  expectContact(ShapeKind<PlaneCollider>::contact(ground, Vec3(3, 4, 0.05), 0.1, 0.0),
                Vec3::UnitZ(), 0.05);
  EXPECT_FALSE(ShapeKind<PlaneCollider>::contact(ground, Vec3(0, 0, 0.2), 0.1, 0.0));
  EXPECT_FALSE(
      ShapeKind<PlaneCollider>::contact(ground, Vec3(0, 0, 0.1), 0.1, 0.0));  // just touching
  expectContact(ShapeKind<PlaneCollider>::contact(ground, Vec3(0, 0, -2.0), 0.1, 0.0),
                Vec3::UnitZ(), 2.1);                     // half-space
  PlaneCollider wall{Vec3(-1, 0, 0), -3.0, Material{}};  // solid where -x < -3, i.e. x > 3
  expectContact(ShapeKind<PlaneCollider>::contact(wall, Vec3(2.95, 0, 0), 0.1, 0.0), Vec3(-1, 0, 0),
                0.05);
}

TEST(SphereVsSphere, HitsMissesAndConcentric) {
  expectContact(sphereAgainstBall(Vec3(1.5, 0, 0), 0.6, Vec3::Zero(), 1.0, 0.0), Vec3::UnitX(),
                0.1);
  EXPECT_FALSE(sphereAgainstBall(Vec3(0, 1.7, 0), 0.6, Vec3::Zero(), 1.0, 0.0));
  EXPECT_FALSE(sphereAgainstBall(Vec3(0, 1.6, 0), 0.6, Vec3::Zero(), 1.0, 0.0));  // touching
  expectContact(sphereAgainstBall(Vec3::Zero(), 0.5, Vec3::Zero(), 1.0, 0.0), Vec3::UnitZ(), 1.5);
}

TEST(SphereVsBox, FacesEdgesCornersAndInside) {
  BoxCollider box;  // unit half extents at the origin
  expectContact(ShapeKind<BoxCollider>::contact(box, Vec3(1.05, 0.2, -0.3), 0.1, 0.0),
                Vec3::UnitX(), 0.05);
  EXPECT_FALSE(ShapeKind<BoxCollider>::contact(box, Vec3(1.2, 0, 0), 0.1, 0.0));
  // Edge: nearest point (1, 1, z), normal along the diagonal of x and y.
  const Real s = 0.05 / std::sqrt(2.0);
  expectContact(ShapeKind<BoxCollider>::contact(box, Vec3(1 + s, 1 + s, 0.5), 0.1, 0.0),
                Vec3(1, 1, 0).normalized(), 0.05);
  // Near an edge but outside the sphere's reach diagonally, though within reach per axis.
  EXPECT_FALSE(ShapeKind<BoxCollider>::contact(box, Vec3(1.08, 1.08, 0.0), 0.1, 0.0));
  // Corner.
  const Real c = 0.05 / std::sqrt(3.0);
  expectContact(ShapeKind<BoxCollider>::contact(box, Vec3(-1 - c, 1 + c, -1 - c), 0.1, 0.0),
                Vec3(-1, 1, -1).normalized(), 0.05);
  // Inside: out through the nearest face.
  expectContact(ShapeKind<BoxCollider>::contact(box, Vec3(0.2, -0.9, 0.0), 0.1, 0.0),
                -Vec3::UnitY(), 0.2);
}

TEST(SphereVsBox, OrientedBoxUsesItsOwnAxes) {
  BoxCollider box;
  box.center = Vec3(1, 2, 3);
  box.half_extents = Vec3(2.0, 0.5, 0.5);
  box.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitZ()));
  // The long axis now lies along y: a point 1.9 m along y from the centre is inside the box.
  const auto inside =
      ShapeKind<BoxCollider>::contact(box, box.center + Vec3(0.0, 1.9, 0.0), 0.05, 0.0);
  expectContact(inside, Vec3::UnitY(), 0.15);
  // Beyond the rotated short axis (x), it misses; along x at 0.55 it hits the face x = 0.5.
  EXPECT_FALSE(ShapeKind<BoxCollider>::contact(box, box.center + Vec3(0.7, 0.0, 0.0), 0.1, 0.0));
  expectContact(ShapeKind<BoxCollider>::contact(box, box.center + Vec3(0.55, 0.0, 0.0), 0.1, 0.0),
                Vec3::UnitX(), 0.05);
}

// The box and ball tests reject far spheres from the squared distance (certainlyBeyond); at the
// edge of their reach they must decide as the test on the distance itself does, to the bit.
TEST(SphereVsShapes, TheSquaredDistanceRejectsOnlyWhatTheDistanceTestRejects) {
  BoxCollider box;
  box.center = Vec3::Zero();
  box.half_extents = Vec3(0.5, 0.25, 0.75);
  const Vec3 corner_direction = Vec3(1.0, 2.0, 3.0).normalized();
  const Vec3 box_corner = box.half_extents;
  const Vec3 ball_center(0.3, -0.2, 0.1);
  const Real ball_radius = 0.7;
  int near_edge = 0;
  for (const Real r : {0.025, 0.1, 0.3}) {
    for (const Real margin : {0.0, 1e-4, 0.02}) {
      for (int k = -2000; k <= 2000; ++k) {
        const Real distance = (r + margin) * (1.0 + k * 1e-16);
        const Vec3 x = box_corner + distance * corner_direction;
        const Vec3 outside = x - x.cwiseMax(-box.half_extents).cwiseMin(box.half_extents);
        const bool box_expected = r - outside.norm() > -margin;
        EXPECT_EQ(ShapeKind<BoxCollider>::contact(box, x, r, margin).has_value(), box_expected)
            << r << " " << margin << " " << k;

        const Vec3 y = ball_center + (ball_radius + distance) * corner_direction;
        const bool ball_expected = r + ball_radius - (y - ball_center).norm() > -margin;
        EXPECT_EQ(sphereAgainstBall(y, r, ball_center, ball_radius, margin).has_value(),
                  ball_expected)
            << r << " " << margin << " " << k;
        near_edge += (box_expected ? 1 : 0) + (ball_expected ? 1 : 0);
      }
    }
  }
  // Both answers occur near the edge (the sweep straddles it).
  EXPECT_GT(near_edge, 0);
  EXPECT_LT(near_edge, 2 * 9 * 4001);
  // Far away: none, without reaching the square root.
  EXPECT_FALSE(ShapeKind<BoxCollider>::contact(box, Vec3(10, 10, 10), 0.1, 0.01));
  EXPECT_FALSE(sphereAgainstBall(Vec3(10, 10, 10), 0.1, ball_center, ball_radius, 0.01));
}

TEST(SphereVsCapsule, SideEndCapsAndAxis) {
  CapsuleCollider capsule{Vec3(0, 0, 0), Vec3(0, 0, 2), 0.5, Material{}};
  expectContact(ShapeKind<CapsuleCollider>::contact(capsule, Vec3(0.55, 0, 1.0), 0.1, 0.0),
                Vec3::UnitX(), 0.05);
  expectContact(ShapeKind<CapsuleCollider>::contact(capsule, Vec3(0, 0, 2.55), 0.1, 0.0),
                Vec3::UnitZ(), 0.05);
  expectContact(ShapeKind<CapsuleCollider>::contact(capsule, Vec3(0, 0, -0.55), 0.1, 0.0),
                -Vec3::UnitZ(), 0.05);
  const Real d = 0.55 / std::sqrt(2.0);
  expectContact(ShapeKind<CapsuleCollider>::contact(capsule, Vec3(d, 0, 2 + d), 0.1, 0.0),
                Vec3(1, 0, 1).normalized(), 0.05);
  EXPECT_FALSE(ShapeKind<CapsuleCollider>::contact(capsule, Vec3(0.7, 0, 1.0), 0.1, 0.0));
  EXPECT_FALSE(ShapeKind<CapsuleCollider>::contact(capsule, Vec3(0.0, 0, 2.7), 0.1, 0.0));
  // Degenerate capsule (a == b) is a sphere.
  CapsuleCollider point{Vec3(1, 1, 1), Vec3(1, 1, 1), 0.5, Material{}};
  expectContact(ShapeKind<CapsuleCollider>::contact(point, Vec3(1, 1, 1.55), 0.1, 0.0),
                Vec3::UnitZ(), 0.05);
}

TEST(RayVsShapes, HitsMissesEdgesAndStartsInside) {
  const Vec3 down = -Vec3::UnitZ();
  PlaneCollider ground;
  auto hit = ShapeKind<PlaneCollider>::raycast(ground, Vec3(0, 0, 5), down, 10.0, 0.0);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, 5.0, kTol);
  hit = ShapeKind<PlaneCollider>::raycast(ground, Vec3(0, 0, 5), down, 10.0,
                                          0.5);  // grown by a swept radius
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, 4.5, kTol);
  EXPECT_FALSE(
      ShapeKind<PlaneCollider>::raycast(ground, Vec3(0, 0, 5), down, 4.0, 0.0));  // too short
  EXPECT_FALSE(ShapeKind<PlaneCollider>::raycast(ground, Vec3(0, 0, 5), Vec3::UnitX(), 10.0,
                                                 0));  // parallel
  EXPECT_FALSE(
      ShapeKind<PlaneCollider>::raycast(ground, Vec3(0, 0, -1), down, 10.0, 0.0));  // inside

  hit = rayIntoBall(Vec3(-5, 0, 0), Vec3::UnitX(), 10.0, Vec3::Zero(), 1.0);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, 4.0, kTol);
  EXPECT_NEAR((hit->normal + Vec3::UnitX()).norm(), 0.0, kTol);
  // Grazing: tangent at y = 1 still hits; y = 1.001 misses.
  EXPECT_TRUE(rayIntoBall(Vec3(-5, 1.0, 0), Vec3::UnitX(), 10.0, Vec3::Zero(), 1.0));
  EXPECT_FALSE(rayIntoBall(Vec3(-5, 1.001, 0), Vec3::UnitX(), 10.0, Vec3::Zero(), 1.0));
  EXPECT_FALSE(rayIntoBall(Vec3(5, 0, 0), Vec3::UnitX(), 10.0, Vec3::Zero(), 1.0));    // behind
  EXPECT_FALSE(rayIntoBall(Vec3(0.5, 0, 0), Vec3::UnitX(), 10.0, Vec3::Zero(), 1.0));  // inside

  BoxCollider box;
  hit = ShapeKind<BoxCollider>::raycast(box, Vec3(-5, 0.3, 0.2), Vec3::UnitX(), 10.0, 0.0);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, 4.0, kTol);
  EXPECT_NEAR((hit->normal + Vec3::UnitX()).norm(), 0.0, kTol);
  // Diagonal ray through a corner region enters through the face crossed last.
  hit =
      ShapeKind<BoxCollider>::raycast(box, Vec3(-3, -2, 0), Vec3(1, 1, 0).normalized(), 10.0, 0.0);
  ASSERT_TRUE(hit);
  EXPECT_NEAR((hit->normal + Vec3::UnitX()).norm(), 0.0, kTol);
  EXPECT_NEAR(hit->t, 2.0 * std::sqrt(2.0), kTol);
  EXPECT_FALSE(ShapeKind<BoxCollider>::raycast(box, Vec3(-5, 1.01, 0), Vec3::UnitX(), 10.0, 0.0));
  EXPECT_TRUE(
      ShapeKind<BoxCollider>::raycast(box, Vec3(-5, 1.01, 0), Vec3::UnitX(), 10.0, 0.05));  // grown
  EXPECT_FALSE(
      ShapeKind<BoxCollider>::raycast(box, Vec3(0, 0, 0), Vec3::UnitX(), 10.0, 0.0));  // inside
  BoxCollider turned;
  turned.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 4, Vec3::UnitZ()));
  hit = ShapeKind<BoxCollider>::raycast(turned, Vec3(-5, 0, 0), Vec3::UnitX(), 10.0, 0.0);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, 5.0 - std::sqrt(2.0), 1e-12);  // the corner of the turned square

  CapsuleCollider capsule{Vec3(0, 0, -1), Vec3(0, 0, 1), 0.5, Material{}};
  hit = ShapeKind<CapsuleCollider>::raycast(capsule, Vec3(-5, 0, 0.3), Vec3::UnitX(), 10.0, 0.0);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, 4.5, kTol);
  EXPECT_NEAR((hit->normal + Vec3::UnitX()).norm(), 0.0, kTol);
  hit = ShapeKind<CapsuleCollider>::raycast(capsule, Vec3(0, 0, 5), down, 10.0,
                                            0.0);  // down the axis: end cap
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, 3.5, kTol);
  EXPECT_NEAR((hit->normal - Vec3::UnitZ()).norm(), 0.0, kTol);
  EXPECT_FALSE(
      ShapeKind<CapsuleCollider>::raycast(capsule, Vec3(-5, 0.6, 0), Vec3::UnitX(), 10.0, 0.0));
  EXPECT_TRUE(
      ShapeKind<CapsuleCollider>::raycast(capsule, Vec3(-5, 0.6, 0), Vec3::UnitX(), 10.0, 0.2));
  EXPECT_FALSE(ShapeKind<CapsuleCollider>::raycast(capsule, Vec3(0, 0.2, 0), Vec3::UnitX(), 10.0,
                                                   0.0));  // inside
}

TEST(SweptSpheres, TimeOfImpact) {
  // a starts 10 m from b and closes 20 m over the step: touches (sum of radii 1) at s = 0.45.
  auto s = sweptSpheresTimeOfImpact(Vec3(10, 0, 0), Vec3(-20, 0, 0), 1.0);
  ASSERT_TRUE(s);
  EXPECT_NEAR(*s, 0.45, kTol);
  EXPECT_FALSE(sweptSpheresTimeOfImpact(Vec3(10, 0, 0), Vec3(20, 0, 0), 1.0));   // apart
  EXPECT_FALSE(sweptSpheresTimeOfImpact(Vec3(10, 0, 0), Vec3(-5, 0, 0), 1.0));   // short
  EXPECT_FALSE(sweptSpheresTimeOfImpact(Vec3(10, 2, 0), Vec3(-20, 0, 0), 1.0));  // passes by
  EXPECT_FALSE(sweptSpheresTimeOfImpact(Vec3(0.5, 0, 0), Vec3(-1, 0, 0), 1.0));  // overlapping
}

TEST(WorldColliders, ValidatesAddsAndRemoves) {
  World world;
  EXPECT_FALSE(world.addCollider(PlaneCollider{Vec3::Zero(), 0.0, Material{}}).isOk());
  EXPECT_FALSE(world.addCollider(SphereCollider{Vec3::Zero(), -1.0, Material{}}).isOk());
  BoxCollider flat;
  flat.half_extents = Vec3(1, 0, 1);
  EXPECT_FALSE(world.addCollider(flat).isOk());
  CapsuleCollider nan_capsule;
  nan_capsule.a.x() = std::nan("");
  EXPECT_FALSE(world.addCollider(nan_capsule).isOk());
  PlaneCollider bouncy;
  bouncy.material.restitution = 1.5;
  EXPECT_FALSE(world.addCollider(bouncy).isOk());
  EXPECT_TRUE(world.colliders().empty());

  // Scaled normals are normalised with the offset: 2z < 4 is z < 2.
  const auto plane = world.addCollider(PlaneCollider{Vec3(0, 0, 2), 4.0, Material{}});
  ASSERT_TRUE(plane.isOk());
  EXPECT_NEAR(world.colliders().of<PlaneCollider>()[0].offset, 2.0, kTol);
  const auto sphere = world.addCollider(SphereCollider{});
  const auto box = world.addCollider(BoxCollider{});
  const auto capsule = world.addCollider(CapsuleCollider{});
  ASSERT_TRUE(sphere && box && capsule);
  EXPECT_NE(*plane, *sphere);
  EXPECT_EQ(world.colliders().size(), 4u);
  EXPECT_TRUE(world.removeCollider(*box).isOk());
  EXPECT_FALSE(world.removeCollider(*box).isOk());
  EXPECT_EQ(world.colliders().of<BoxCollider>().size(), 0u);
  EXPECT_EQ(world.colliders().size(), 3u);
}

// A particle dropped onto each shape comes to rest on top of it.
TEST(WorldColliders, ParticleRestsOnEveryShape) {
  for (int shape = 0; shape < 5; ++shape) {
    WorldConfig config;
    config.gravity = Vec3(0, 0, -9.81);
    World world(config);
    Material material{0.3, 0.0};
    Real top = 0.0;
    switch (shape) {
      case 0:
        ASSERT_TRUE(world.addCollider(PlaneCollider{Vec3::UnitZ(), 0.0, material}).isOk());
        break;
      case 1:
        ASSERT_TRUE(world.addCollider(SphereCollider{Vec3(0, 0, -1), 1.0, material}).isOk());
        break;
      case 2: {
        BoxCollider box;
        box.center = Vec3(0, 0, -1);
        box.material = material;
        ASSERT_TRUE(world.addCollider(box).isOk());
        break;
      }
      case 3: {
        BoxCollider box;
        box.center = Vec3(0, 0, -1);
        // Turned about z only: its top face stays at z = 0.
        box.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Vec3::UnitZ()));
        box.material = material;
        ASSERT_TRUE(world.addCollider(box).isOk());
        break;
      }
      case 4:
        ASSERT_TRUE(
            world.addCollider(CapsuleCollider{Vec3(-1, 0, -0.5), Vec3(1, 0, -0.5), 0.5, material})
                .isOk());
        break;
    }
    ParticleSpec spec;
    spec.position = Vec3(0, 0, top + 1.0);
    spec.radius = 0.1;
    ASSERT_TRUE(world.addParticle(spec).isOk());
    for (int s = 0; s < 300; ++s) world.step();
    const Vec3 x = world.particles().positions().col(0);
    EXPECT_NEAR(x.z(), top + 0.1, world.collisionSettings().penetration_slop) << "shape " << shape;
    EXPECT_LT(world.particles().velocities().col(0).norm(), 1e-6) << "shape " << shape;
  }
}

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
