#include <gtest/gtest.h>

#include <cmath>

#include "mass_aggregate_sim/engine/world/world.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

ParticleSpec ball(const Vec3& position, const Vec3& velocity, const Real mass, const Real radius) {
  ParticleSpec spec;
  spec.position = position;
  spec.velocity = velocity;
  spec.inverse_mass = 1.0 / mass;
  spec.radius = radius;
  return spec;
}

World zeroGravityWorld(const Real restitution) {
  World world;
  CollisionSettings settings;
  settings.particle_collisions = true;
  settings.particle_restitution = restitution;
  EXPECT_TRUE(world.setCollisionSettings(settings).isOk());
  return world;
}

Vec3 velocityOf(const World& world, const ParticleId id) {
  return world.particles().velocities().col(*world.particles().find(id));
}

TEST(ParticleCollision, HeadOnConservesMomentumAndScalesNormalVelocityByRestitution) {
  for (const Real e : {0.0, 0.3, 0.5, 0.8, 1.0}) {
    World world = zeroGravityWorld(e);
    // Oblique approach, unequal masses: the normal part reverses scaled by e, the tangential
    // part is untouched (no friction).
    const ParticleId a = *world.addParticle(ball({0.0, 0.0, 0.0}, {2.0, 0.3, 0.0}, 1.0, 0.5));
    const ParticleId b = *world.addParticle(ball({0.99, 0.0, 0.0}, {-1.0, 0.0, 0.1}, 3.0, 0.5));
    const Vec3 momentum_before = world.linearMomentum();
    const Real ke_before = world.kineticEnergy();
    world.step();
    ASSERT_EQ(world.lastContactStats().contacts, 1u);
    const auto x = world.particles().positions();
    const Vec3 normal =
        (Vec3(x.col(*world.particles().find(a))) - x.col(*world.particles().find(b))).normalized();
    const Vec3 relative = velocityOf(world, a) - velocityOf(world, b);
    EXPECT_NEAR((world.linearMomentum() - momentum_before).norm(), 0.0, 1e-14);
    // Before: (v_a - v_b) = (3, 0.3, -0.1), normal ~ -x, so v_sep = -3 (closing).
    const Real v_sep_before = Vec3(3.0, 0.3, -0.1).dot(normal);
    EXPECT_NEAR(relative.dot(normal), -e * v_sep_before, 1e-14) << "e = " << e;
    const Vec3 tangential_before = Vec3(3.0, 0.3, -0.1) - v_sep_before * normal;
    EXPECT_NEAR((relative - relative.dot(normal) * normal - tangential_before).norm(), 0.0, 1e-14);
    if (e == 1.0) {
      EXPECT_NEAR(world.kineticEnergy(), ke_before, 1e-13);
    } else {
      EXPECT_LT(world.kineticEnergy(), ke_before);
    }
  }
}

TEST(ParticleCollision, NewtonsCradlePassesTheImpulseAlong) {
  World world = zeroGravityWorld(1.0);
  std::vector<ParticleId> balls;
  // Five balls 1 cm apart (a real cradle's balls are never perfectly touching), the first moving
  // into the row: each collision happens on its own, and the last ball leaves with all the speed.
  for (int i = 0; i < 5; ++i) {
    const Vec3 position(0.21 * i - (i == 0 ? 0.05 : 0.0), 0.0, 0.0);
    balls.push_back(*world.addParticle(ball(position, Vec3::Zero(), 1.0, 0.1)));
  }
  ASSERT_TRUE(world.setVelocity(balls[0], Vec3(1.0, 0.0, 0.0)).isOk());
  for (int s = 0; s < 60; ++s) world.step();
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(velocityOf(world, balls[i]).norm(), 0.0, 1e-12) << "ball " << i;
  }
  EXPECT_NEAR((velocityOf(world, balls[4]) - Vec3(1.0, 0.0, 0.0)).norm(), 0.0, 1e-12);
}

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
