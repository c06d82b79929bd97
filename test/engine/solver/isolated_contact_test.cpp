// Isolated contacts (whose particles are in no other constraint) are solved in the resolver's
// set-up pass. They must move their particles as the general passes do: each scene is run twice,
// once as it is (isolated) and once with a wall 1 mm beside the ball, whose speculative contact
// pushes nothing (the ball does not move towards it) but puts a second contact on the ball, so its
// ground contact goes through the general passes.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "../integrators/integrator_params.h"
#include "engine/solver/contact_resolver.h"
#include "mass_aggregate_sim/engine/world/world.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

constexpr Real kRadius = 0.1;
constexpr Real kTight = 1e-12;

struct BallScene {
  Integrator integrator = Integrator::kSemiImplicitEuler;
  Real drop = 0.3;  // height of the ball's bottom above the ground
  Real restitution = 0.2;
  Real friction = 0.0;
  Vec3 velocity = Vec3::Zero();
  bool wall_beside = false;  // a wall 1 mm from the ball, in the contact margin
};

World ballWorld(const BallScene& scene) {
  WorldConfig config;
  config.dt = 1.0 / 60.0;
  config.substeps = 1;
  config.integrator = scene.integrator;
  config.gravity = Vec3(0.0, -9.81, 0.0);
  World world(config);
  PlaneCollider ground;
  ground.normal = Vec3::UnitY();
  ground.material.restitution = scene.restitution;
  ground.material.friction = scene.friction;
  EXPECT_TRUE(world.addCollider(ground).isOk());
  if (scene.wall_beside) {
    // Solid where -z < -(r + 1 mm): z > r + 1 mm. The ball never moves along z.
    PlaneCollider wall;
    wall.normal = -Vec3::UnitZ();
    wall.offset = -(kRadius + 0.001);
    EXPECT_TRUE(world.addCollider(wall).isOk());
  }
  ParticleSpec spec;
  spec.position = Vec3(0.0, kRadius + scene.drop, 0.0);
  spec.velocity = scene.velocity;
  spec.radius = kRadius;
  spec.damping = 0.99;
  EXPECT_TRUE(world.addParticle(spec).isOk());
  return world;
}

// Steps the isolated and the general version side by side and compares motion and stats.
void expectSameMotion(BallScene scene, const int steps) {
  scene.wall_beside = false;
  World isolated = ballWorld(scene);
  scene.wall_beside = true;
  World general = ballWorld(scene);
  int steps_in_contact = 0;
  for (int s = 0; s < steps; ++s) {
    isolated.step();
    general.step();
    const Vec3 x_isolated = isolated.particles().positions().col(0);
    const Vec3 x_general = general.particles().positions().col(0);
    const Vec3 v_isolated = isolated.particles().velocities().col(0);
    const Vec3 v_general = general.particles().velocities().col(0);
    ASSERT_LE((x_isolated - x_general).norm(), kTight) << "step " << s;
    ASSERT_LE((v_isolated - v_general).norm(), kTight) << "step " << s;
    const ContactStats& a = isolated.lastContactStats();
    const ContactStats& b = general.lastContactStats();
    ASSERT_EQ(b.contacts, a.contacts + 1) << "step " << s;  // the wall's
    if (a.contacts > 0) ++steps_in_contact;
    ASSERT_NEAR(a.max_penetration, b.max_penetration, kTight) << "step " << s;
    ASSERT_NEAR(a.max_closing_velocity, b.max_closing_velocity, kTight) << "step " << s;
    ASSERT_EQ(isolated.divergenceCount(), 0u);
  }
  EXPECT_GT(steps_in_contact, 20);
}

class IsolatedContact : public ::testing::TestWithParam<Integrator> {};

TEST_P(IsolatedContact, RestingBallMovesAsInTheGeneralPasses) {
  BallScene scene;
  scene.integrator = GetParam();
  scene.drop = 0.0;
  expectSameMotion(scene, 240);
}

TEST_P(IsolatedContact, BouncingBallMovesAsInTheGeneralPasses) {
  BallScene scene;
  scene.integrator = GetParam();
  scene.drop = 0.5;
  scene.restitution = 0.8;
  expectSameMotion(scene, 400);
}

TEST_P(IsolatedContact, SlidingBallWithFrictionMovesAsInTheGeneralPasses) {
  BallScene scene;
  scene.integrator = GetParam();
  scene.drop = 0.05;
  scene.friction = 0.3;
  scene.velocity = Vec3(2.0, 0.0, 0.0);  // along x: parallel to the wall
  expectSameMotion(scene, 240);
}

INSTANTIATE_TEST_SUITE_P(AllIntegrators, IsolatedContact, everyIntegrator(), integratorParamName);

// The stats of an isolated contact: overlap left after the correction, closing speed left.
TEST(IsolatedContactStats, BallPushedIntoTheGroundIsCorrectedAndReported) {
  BallScene scene;
  scene.drop = -0.02;  // 2 cm into the ground: beyond the slop
  World world = ballWorld(scene);
  world.step();
  const ContactStats& stats = world.lastContactStats();
  const Real slop = world.collisionSettings().penetration_slop;
  ASSERT_EQ(stats.contacts, 1u);
  // Corrected down to half the slop, and the pass that measured it counted.
  EXPECT_NEAR(stats.max_penetration, 0.5 * slop, 1e-12);
  EXPECT_EQ(stats.position_iterations, 2);
  EXPECT_NEAR(world.particles().positions()(1, 0), kRadius - 0.5 * slop, 1e-12);
  EXPECT_LE(stats.max_closing_velocity, 1e-12);
}

TEST(IsolatedContactStats, FastImpactReportsNoClosingSpeedLeft) {
  BallScene scene;
  scene.drop = 0.0;
  scene.velocity = Vec3(0.0, -5.0, 0.0);
  scene.restitution = 0.5;
  World world = ballWorld(scene);
  world.step();
  ASSERT_EQ(world.lastContactStats().contacts, 1u);
  // Bounced: moving up, nothing closing.
  EXPECT_GT(world.particles().velocities()(1, 0), 0.0);
  EXPECT_LE(world.lastContactStats().max_closing_velocity, 1e-12);
}

// Which contacts the resolver takes as isolated: counted per particle over all contacts.
struct ResolverRun {
  Vec3Array x;
  Vec3Array v;
  ScalarArray inverse_mass;
  Vec3Array acceleration;
  ContactResolver resolver;
  ContactStats stats;

  explicit ResolverRun(const int n)
      : x(Vec3Array::Zero(3, n)),
        v(Vec3Array::Zero(3, n)),
        inverse_mass(ScalarArray::Ones(n)),
        acceleration(Vec3Array::Zero(3, n)) {
    for (int i = 0; i < n; ++i) acceleration.col(i) = Vec3(0.0, -9.81, 0.0);
  }
  std::size_t isolated(std::vector<Contact> contacts) {
    const std::vector<LinkGeometry> links;
    resolver.resolve(contacts, links, Vec3Map(x.data(), 3, x.cols()),
                     Vec3Map(v.data(), 3, v.cols()),
                     ConstScalarMap(inverse_mass.data(), inverse_mass.size()), acceleration,
                     1.0 / 60.0, CollisionSettings{}, 1.0, stats);
    return resolver.isolatedContacts();
  }
};

Contact groundContact(const std::uint32_t a, const std::uint32_t collider) {
  Contact c;
  c.a = a;
  c.normal = Vec3::UnitY();
  c.penetration = 0.0005;
  c.key = colliderContactKey(a, collider);
  return c;
}

Contact pairContact(const std::uint32_t a, const std::uint32_t b) {
  Contact c;
  c.a = a;
  c.b = b;
  c.normal = Vec3::UnitX();
  c.penetration = 0.0005;
  c.key = pairContactKey(a, b);
  return c;
}

TEST(IsolatedContactClassification, OneContactPerParticleIsIsolated) {
  ResolverRun run(3);
  EXPECT_EQ(run.isolated({groundContact(0, 1), groundContact(1, 1), groundContact(2, 1)}), 3u);
}

TEST(IsolatedContactClassification, BallInACornerGoesTheGeneralWay) {
  // Particle 0 touches two planes: neither of its contacts is isolated; particle 1's is.
  ResolverRun run(2);
  EXPECT_EQ(run.isolated({groundContact(0, 1), groundContact(1, 1), groundContact(0, 2)}), 1u);
}

TEST(IsolatedContactClassification, PairsAndLinksShareTheirParticles) {
  ResolverRun run(5);
  // 0-1 a lone pair (isolated), 2 on the ground and touching 3 (neither isolated), 4 alone.
  EXPECT_EQ(run.isolated(
                {groundContact(2, 1), groundContact(4, 1), pairContact(0, 1), pairContact(2, 3)}),
            2u);
  // A link is never solved as isolated, and its particle's contact is not either.
  Contact rod;
  rod.a = 4;
  rod.kind = ContactKind::kRod;
  rod.link = 0;
  rod.key = linkContactKey(7);
  std::vector<Contact> contacts = {groundContact(4, 1), rod};
  const std::vector<LinkGeometry> links = {LinkGeometry{Vec3(0.0, 1.0, 0.0), 1.0}};
  run.resolver.resolve(contacts, links, Vec3Map(run.x.data(), 3, run.x.cols()),
                       Vec3Map(run.v.data(), 3, run.v.cols()),
                       ConstScalarMap(run.inverse_mass.data(), run.inverse_mass.size()),
                       run.acceleration, 1.0 / 60.0, CollisionSettings{}, 1.0, run.stats);
  EXPECT_EQ(run.resolver.isolatedContacts(), 0u);
}

// A lone ball moves as when alone beside a stack of two (particle collisions on): with particle
// pairs the world resolves every contact as a row (isolated ones are looked for only when all
// contacts are with colliders), alone its contact is isolated.
TEST(IsolatedContactMix, LoneBallBesideAPairMovesAsWhenAlone) {
  const auto make = [](const bool with_pair) {
    WorldConfig config;
    config.dt = 1.0 / 60.0;
    config.gravity = Vec3(0.0, -9.81, 0.0);
    World world(config);
    CollisionSettings collisions;
    collisions.particle_collisions = true;
    collisions.particle_restitution = 0.3;
    EXPECT_TRUE(world.setCollisionSettings(collisions));
    PlaneCollider ground;
    ground.normal = Vec3::UnitY();
    ground.material.restitution = 0.2;
    EXPECT_TRUE(world.addCollider(ground).isOk());
    ParticleSpec spec;
    spec.radius = kRadius;
    spec.damping = 0.99;
    spec.position = Vec3(0.0, kRadius + 0.2, 0.0);
    EXPECT_TRUE(world.addParticle(spec).isOk());
    if (with_pair) {
      // Far from the lone ball; a stack of two: the lower one is in two contacts.
      spec.position = Vec3(5.0, kRadius + 0.1, 0.0);
      EXPECT_TRUE(world.addParticle(spec).isOk());
      spec.position = Vec3(5.0, 3.0 * kRadius + 0.1, 0.0);
      EXPECT_TRUE(world.addParticle(spec).isOk());
    }
    return world;
  };
  World alone = make(false);
  World mixed = make(true);
  bool stacked = false;
  for (int s = 0; s < 300; ++s) {
    alone.step();
    mixed.step();
    ASSERT_LE(
        (Vec3(alone.particles().positions().col(0)) - Vec3(mixed.particles().positions().col(0)))
            .norm(),
        kTight)
        << "step " << s;
    ASSERT_LE(
        (Vec3(alone.particles().velocities().col(0)) - Vec3(mixed.particles().velocities().col(0)))
            .norm(),
        kTight)
        << "step " << s;
    stacked = stacked || mixed.lastContactStats().contacts == 3;
  }
  EXPECT_TRUE(stacked);
  // The stack settles on the ground, the upper ball on the lower one.
  const auto x = mixed.particles().positions();
  EXPECT_NEAR(x(1, 1), kRadius, 2e-3);
  EXPECT_NEAR(x(1, 2), 3.0 * kRadius, 4e-3);
  EXPECT_NEAR(x(0, 2), 5.0, 1e-9);
  EXPECT_LT(mixed.particles().velocities().norm(), 1e-6);
}

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
