// With only collider contacts (no particle collisions, no links) the world makes and solves them in
// parts of 256 particles (solveColliderContactsInParts), four consecutive particles at a time in
// vector lanes without writing a Contact where each meets one collider at most
// (solveColliderGroups), the rest as Contacts; with a contact limit it makes them all first and
// resolves them at once. Both must give bit-identical states, warm starts included (stateHash),
// and the same stats: the scene mixes resting, bouncing and sliding balls, balls in the corners of
// a box (two contacts: rows), friction and every collider shape, over more than two parts; and the
// same with frictionless planes only.
#include <gtest/gtest.h>

#include <cmath>

#include "../integrators/integrator_params.h"
#include "mass_aggregate_sim/engine/world/world.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

constexpr int kBalls = 700;  // three parts: 256, 256, 188

void addShapes(World& world);
void addBalls(World& world);

struct BoxScene {
  bool planes_only = false;  // no sphere, box or capsule, and no friction
  std::size_t max_contacts = 0;
};

World boxWorld(const Integrator integrator, const BoxScene& scene) {
  WorldConfig config;
  config.dt = 1.0 / 60.0;
  config.integrator = integrator;
  config.gravity = Vec3(0.0, -9.81, 0.0);
  World world(config);
  CollisionSettings settings;
  settings.max_contacts = scene.max_contacts;
  EXPECT_TRUE(world.setCollisionSettings(settings));
  // A 4 m box: floor (with friction) and four walls (without); a sphere, a box and a capsule on
  // the floor.
  const Real floor_friction = scene.planes_only ? 0.0 : 0.4;
  EXPECT_TRUE(
      world.addCollider(PlaneCollider{Vec3::UnitY(), 0.0, Material{0.3, floor_friction}}).isOk());
  EXPECT_TRUE(world.addCollider(PlaneCollider{Vec3::UnitX(), -2.0, Material{0.5, 0.0}}).isOk());
  EXPECT_TRUE(world.addCollider(PlaneCollider{-Vec3::UnitX(), -2.0, Material{0.5, 0.0}}).isOk());
  EXPECT_TRUE(world.addCollider(PlaneCollider{Vec3::UnitZ(), -2.0, Material{0.5, 0.0}}).isOk());
  EXPECT_TRUE(world.addCollider(PlaneCollider{-Vec3::UnitZ(), -2.0, Material{0.5, 0.0}}).isOk());
  if (!scene.planes_only) addShapes(world);
  addBalls(world);
  return world;
}

void addShapes(World& world) {
  SphereCollider sphere;
  sphere.center = Vec3(1.0, 0.0, 1.0);
  sphere.radius = 0.5;
  EXPECT_TRUE(world.addCollider(sphere).isOk());
  BoxCollider box;
  box.center = Vec3(-1.0, 0.2, 1.0);
  box.half_extents = Vec3(0.4, 0.2, 0.3);
  EXPECT_TRUE(world.addCollider(box).isOk());
  CapsuleCollider capsule;
  capsule.a = Vec3(-1.0, 0.2, -1.0);
  capsule.b = Vec3(1.0, 0.2, -1.0);
  capsule.radius = 0.2;
  EXPECT_TRUE(world.addCollider(capsule).isOk());
}

void addBalls(World& world) {
  // A 26 x 26 grid over the floor (its edge rows in the walls' reach, its corners in two), at
  // heights and speeds that vary from ball to ball, some resting from the start.
  for (int i = 0; i < kBalls; ++i) {
    const int row = i / 26;
    const int column = i % 26;
    ParticleSpec spec;
    spec.radius = 0.05;
    spec.position = Vec3(-1.95 + 0.156 * column, 0.05 + 0.1 * (i % 7 == 0 ? 0 : (i % 5)),
                         -1.95 + 0.156 * (row % 26));
    spec.velocity = Vec3(0.3 * std::sin(i), -0.5 * (i % 3), 0.3 * std::cos(i));
    spec.inverse_mass = 1.0 / (1.0 + 0.1 * (i % 4));
    spec.damping = 0.99;
    EXPECT_TRUE(world.addParticle(spec).isOk());
  }
}

class ColliderContactParts : public ::testing::TestWithParam<Integrator> {};

void expectSameStateAsAllAtOnce(const Integrator integrator, BoxScene scene) {
  scene.max_contacts = 0;
  World in_parts = boxWorld(integrator, scene);
  scene.max_contacts = 1000000;
  World at_once = boxWorld(integrator, scene);
  int steps_with_corners = 0;
  for (int s = 0; s < 180; ++s) {
    in_parts.step();
    at_once.step();
    ASSERT_EQ(in_parts.stateHash(), at_once.stateHash()) << "step " << s;
    const ContactStats& a = in_parts.lastContactStats();
    const ContactStats& b = at_once.lastContactStats();
    ASSERT_EQ(a.contacts, b.contacts) << "step " << s;
    ASSERT_EQ(a.velocity_iterations, b.velocity_iterations) << "step " << s;
    ASSERT_EQ(a.position_iterations, b.position_iterations) << "step " << s;
    ASSERT_EQ(a.max_penetration, b.max_penetration) << "step " << s;
    ASSERT_EQ(a.max_closing_velocity, b.max_closing_velocity) << "step " << s;
    // Rows took part: some ball is in two contacts (a corner, a wall and the floor).
    if (a.contacts > static_cast<std::size_t>(kBalls) / 2 && a.velocity_iterations > 1) {
      ++steps_with_corners;
    }
  }
  EXPECT_GT(steps_with_corners, 0);
  EXPECT_EQ(in_parts.divergenceCount(), 0u);
}

TEST_P(ColliderContactParts, SameStateAsAllAtOnce) { expectSameStateAsAllAtOnce(GetParam(), {}); }

TEST_P(ColliderContactParts, FrictionlessPlanesSameStateAsAllAtOnce) {
  BoxScene scene;
  scene.planes_only = true;
  expectSameStateAsAllAtOnce(GetParam(), scene);
}

INSTANTIATE_TEST_SUITE_P(AllIntegrators, ColliderContactParts, everyIntegrator(),
                         integratorParamName);

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
