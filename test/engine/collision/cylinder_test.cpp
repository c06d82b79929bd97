// The cylinder collider, the kind added as one file and one entry in ShapeKinds: its contacts,
// its swept and ray tests, a ball resting on it in a world, and how it is drawn.
#include <gtest/gtest.h>

#include <cmath>

#include "mass_aggregate_sim/engine/world/world.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

using Cylinder = ShapeKind<CylinderCollider>;

// A cylinder of radius 1 and height 2 standing on z = 0 (axis along z, centre at z = 1), given a
// tilted axis to check that the frame is the cylinder's own.
CylinderCollider standing() {
  CylinderCollider c;
  c.center = Vec3(0.0, 0.0, 1.0);
  c.axis = Vec3(0.0, 0.0, 3.0);  // normalised by validate()
  c.radius = 1.0;
  c.half_height = 1.0;
  EXPECT_TRUE(Cylinder::validate(c));
  return c;
}

void expectContact(const std::optional<ShapeContact>& contact, const Vec3& normal,
                   const Real penetration) {
  ASSERT_TRUE(contact.has_value());
  EXPECT_TRUE(contact->normal.isApprox(normal, 1e-12)) << contact->normal.transpose();
  EXPECT_NEAR(contact->penetration, penetration, 1e-12);
}

TEST(CylinderCollider, ValidationNormalisesAndRefuses) {
  const CylinderCollider c = standing();
  EXPECT_TRUE(c.axis.isApprox(Vec3::UnitZ()));
  CylinderCollider bad = c;
  bad.axis = Vec3::Zero();
  EXPECT_FALSE(Cylinder::validate(bad));
  bad = c;
  bad.radius = 0.0;
  EXPECT_FALSE(Cylinder::validate(bad));
  bad = c;
  bad.half_height = std::nan("");
  EXPECT_FALSE(Cylinder::validate(bad));
  bad = c;
  bad.material.restitution = 2.0;
  EXPECT_FALSE(Cylinder::validate(bad));
}

TEST(CylinderCollider, SphereAgainstCapSideRimAndInside) {
  const CylinderCollider c = standing();
  // On the top cap, 5 cm into it.
  expectContact(Cylinder::contact(c, Vec3(0.3, 0.2, 2.05), 0.1, 0.0), Vec3::UnitZ(), 0.05);
  // Against the side.
  expectContact(Cylinder::contact(c, Vec3(0.0, 1.08, 1.0), 0.1, 0.0), Vec3::UnitY(), 0.02);
  // Beyond the rim: the nearest point is on the rim circle.
  const Real s = 0.05 / std::sqrt(2.0);
  expectContact(Cylinder::contact(c, Vec3(1.0 + s, 0.0, 2.0 + s), 0.1, 0.0),
                Vec3(1.0, 0.0, 1.0).normalized(), 0.05);
  // Far away, and just outside the margin.
  EXPECT_FALSE(Cylinder::contact(c, Vec3(0.0, 0.0, 5.0), 0.1, 0.0));
  EXPECT_FALSE(Cylinder::contact(c, Vec3(0.0, 0.0, 2.2), 0.1, 0.05));
  expectContact(Cylinder::contact(c, Vec3(0.0, 0.0, 2.14), 0.1, 0.05), Vec3::UnitZ(), -0.04);
  // Inside: out through the nearer of the side (0.1 away) and the cap (0.5 away).
  expectContact(Cylinder::contact(c, Vec3(-0.9, 0.0, 1.5), 0.1, 0.0), -Vec3::UnitX(), 0.2);
  // Inside near the bottom cap: out downwards (the cylinder is solid).
  expectContact(Cylinder::contact(c, Vec3(0.0, 0.2, 0.05), 0.1, 0.0), -Vec3::UnitZ(), 0.15);
}

TEST(CylinderCollider, RaysHitTheSideAndTheCapsFromOutsideOnly) {
  const CylinderCollider c = standing();
  auto hit = Cylinder::raycast(c, Vec3(-5.0, 0.0, 1.0), Vec3::UnitX(), 10.0, 0.0);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, 4.0, 1e-12);
  EXPECT_TRUE(hit->normal.isApprox(-Vec3::UnitX()));
  hit = Cylinder::raycast(c, Vec3(0.5, 0.0, 6.0), -Vec3::UnitZ(), 10.0, 0.1);  // grown by 0.1
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, 3.9, 1e-12);
  EXPECT_TRUE(hit->normal.isApprox(Vec3::UnitZ()));
  // Passes above the cap, stops short, starts inside.
  EXPECT_FALSE(Cylinder::raycast(c, Vec3(-5.0, 0.0, 2.5), Vec3::UnitX(), 10.0, 0.0));
  EXPECT_FALSE(Cylinder::raycast(c, Vec3(-5.0, 0.0, 1.0), Vec3::UnitX(), 3.0, 0.0));
  EXPECT_FALSE(Cylinder::raycast(c, Vec3(0.0, 0.0, 1.0), Vec3::UnitX(), 10.0, 0.0));
}

TEST(CylinderCollider, ABallDroppedOnItsCapComesToRestThere) {
  WorldConfig config;
  config.gravity = Vec3(0.0, 0.0, -9.81);
  World world(config);
  ASSERT_TRUE(world.addCollider(standing()));
  ParticleSpec spec;
  spec.position = Vec3(0.2, -0.3, 3.0);
  spec.radius = 0.1;
  const ParticleId ball = world.addParticle(spec).value();
  for (int i = 0; i < 300; ++i) world.step();
  const Vec3 x = world.particles().positions().col(*world.particles().find(ball));
  EXPECT_NEAR(x.z(), 2.1, 2e-3);  // on the cap, within the slop
  EXPECT_NEAR(x.x(), 0.2, 1e-9);
  EXPECT_LT(world.kineticEnergy(), 1e-12);
  // The world's queries see it too.
  const auto hit = world.raycast(Vec3(0.0, 0.0, 1.0) + Vec3(-3.0, 0.0, 0.0), Vec3::UnitX(), 10.0);
  ASSERT_TRUE(hit);
  EXPECT_FALSE(hit->hit_particle);
  EXPECT_NEAR(hit->distance, 2.0, 1e-12);
}

TEST(CylinderCollider, DescribedAsOneCylinderAlongItsAxis) {
  CylinderCollider c = standing();
  c.axis = Vec3::UnitX();
  const ShapeDescription d = Cylinder::describe(c);
  ASSERT_EQ(d.parts.size(), 1u);
  EXPECT_EQ(d.parts[0].type, ShapePrimitive::Type::kCylinder);
  EXPECT_TRUE((d.orientation * Vec3::UnitZ()).isApprox(Vec3::UnitX()));
  EXPECT_TRUE(d.parts[0].size.isApprox(Vec3(2.0, 2.0, 2.0)));
  EXPECT_FALSE(d.surface);
}

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
