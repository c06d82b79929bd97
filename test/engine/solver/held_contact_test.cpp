// A particle at rest on something, kicked into it: the contact that held it is hit, and bounces
// as a falling particle's would, on every surface and in both solvers alike.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

#include "mass_aggregate_sim/engine/world/world.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

enum class Surface { kGround, kBoxCollider, kFixedBody, kAwakeBody };

const char* name(const Surface surface) {
  switch (surface) {
    case Surface::kGround:
      return "ground";
    case Surface::kBoxCollider:
      return "box collider";
    case Surface::kFixedBody:
      return "fixed body";
    case Surface::kAwakeBody:
      return "awake body";
  }
  return "?";
}

// A 50 g grain of 5 cm resting 0.5 s on the surface (restitution e everywhere), then set moving
// down at `kick`: the fastest it rises at in the next second.
Real reboundAfterKick(const Surface surface, const Real e, const Real kick) {
  WorldConfig config;
  config.gravity = Vec3(0.0, 0.0, -9.81);
  World world(config);
  const Material material{e, 0.0};
  EXPECT_TRUE(world.addCollider(PlaneCollider{Vec3::UnitZ(), 0.0, material}));
  CollisionSettings collisions;
  collisions.particle_restitution = e;
  EXPECT_TRUE(world.setCollisionSettings(collisions));
  BodySettings bodies;
  bodies.sleep = false;
  EXPECT_TRUE(world.setBodySettings(bodies));
  Real top = 0.0;
  if (surface == Surface::kBoxCollider) {
    EXPECT_TRUE(world.addCollider(BoxCollider{Vec3(0.0, 0.0, 0.25), Vec3::Constant(0.25),
                                              Eigen::Quaterniond::Identity(), material}));
    top = 0.5;
  } else if (surface == Surface::kFixedBody || surface == Surface::kAwakeBody) {
    BodySpec box;
    BodyShapeSpec shape;
    shape.geometry = BoxShape{Vec3::Constant(0.25)};
    shape.material = material;
    box.shapes = {shape};
    box.mass = 1000.0;
    box.pose.position = Vec3(0.0, 0.0, 0.25);
    if (surface == Surface::kFixedBody) box.type = BodyType::kFixed;
    EXPECT_TRUE(world.addBody(box));
    top = 0.5;
  }
  ParticleSpec grain;
  grain.radius = 0.05;
  grain.inverse_mass = 20.0;
  grain.position = Vec3(0.0, 0.0, top + grain.radius);
  const ParticleId id = *world.addParticle(grain);
  for (int i = 0; i < 30; ++i) world.step();
  EXPECT_TRUE(world.setVelocity(id, Vec3(0.0, 0.0, -kick)));
  Real rebound = 0.0;
  for (int i = 0; i < 60; ++i) {
    world.step();
    rebound = std::max(rebound, world.particles().velocities()(2, *world.particles().find(id)));
  }
  return rebound;
}

// The particle solver held a contact that had pushed in the last substep whatever its closing
// speed: kicked down at 1.72, 3 and 6 m/s a grain did not bounce off the ground, a box collider
// or a fixed body, where the body solver bounced it off an awake body at e v. A held contact
// that closes faster than 1 m/s (the bodies' restitution threshold) is now hit; slower, it holds
// in both solvers.
TEST(HeldContact, AParticleKickedIntoWhatHoldsItBouncesOnEverySurface) {
  constexpr Real kRestitution = 0.8;
  for (const Surface surface :
       {Surface::kGround, Surface::kBoxCollider, Surface::kFixedBody, Surface::kAwakeBody}) {
    for (const Real kick : {1.72, 3.0, 6.0}) {
      const Real rebound = reboundAfterKick(surface, kRestitution, kick);
      std::printf("[ held ] %s, kicked at %.2f m/s: rebound %.4f m/s (e v = %.4f)\n", name(surface),
                  kick, rebound, kRestitution * kick);
      // The awake body (1000 kg) gives a little under the kick.
      EXPECT_NEAR(rebound, kRestitution * kick, 0.02 * kRestitution * kick)
          << name(surface) << " at " << kick << " m/s";
    }
    // Below the threshold the contact holds.
    EXPECT_LT(reboundAfterKick(surface, kRestitution, 0.5), 1e-3) << name(surface);
  }
}

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
