#pragma once
// Grains poured into a bin: an open box of five boxes (floor 1.3 m square and 10 cm thick, walls
// 60 cm high, 50 kg) on the ground, and N grains of 2.5 cm radius and 20 g (particle friction 0.3,
// restitution 0.1) dropped into it from a loose block 18 grains square, 6 cm apart, from 0.4 m up
// with up to 5 mm of jitter. 60 Hz, z up, the default body settings (4 substeps, 2 iterations).
// The bin is a dynamic body, or (`as_colliders`) the same five boxes as static colliders: the
// particles' own pile, the floor a body bin is measured against.

#include <algorithm>
#include <cmath>
#include <random>

#include "mass_aggregate_sim/engine/world/world.h"

namespace mass_aggregate_sim {
namespace engine {
namespace grain_bin {

constexpr Real kInside = 0.6;  // half the bin's inner width (m)
constexpr Real kWall = 0.05;   // half a wall's thickness
constexpr Real kHeight = 0.6;  // the walls' height above the floor
constexpr Real kGrainRadius = 0.025;
constexpr Real kGrainMass = 0.02;
constexpr int kStepsPerSecond = 60;

struct Scene {
  World world;
  BodyId bin;        // none with the colliders
  Real bin_z = 0.0;  // where the bin's centre of mass rests
};

inline Scene makeScene(const int grains, const bool as_colliders, const unsigned seed = 1) {
  WorldConfig config;
  config.dt = 1.0 / kStepsPerSecond;
  config.gravity = Vec3(0.0, 0.0, -9.81);
  Scene scene{World(config), BodyId{}};
  World& world = scene.world;
  CollisionSettings collisions;
  collisions.particle_collisions = true;
  collisions.broadphase = Broadphase::kUniformGrid;
  collisions.particle_restitution = 0.1;
  collisions.particle_friction = 0.3;
  world.setCollisionSettings(collisions);
  world.addCollider(PlaneCollider{Vec3::UnitZ(), 0.0, Material{0.1, 0.6}});
  const Material material{0.0, 0.6};
  BodySpec bin;
  const auto add = [&](const Vec3& half_extents, const Vec3& at) {
    if (as_colliders) {
      BoxCollider box;
      box.center = at;
      box.half_extents = half_extents;
      box.material = material;
      world.addCollider(box);
      return;
    }
    BodyShapeSpec shape;
    shape.geometry = BoxShape{half_extents};
    shape.material = material;
    shape.local.position = at;
    bin.shapes.push_back(shape);
  };
  const Real outer = kInside + kWall;
  const Real wall_z = 2.0 * kWall + 0.5 * kHeight;
  add(Vec3(outer, outer, kWall), Vec3(0.0, 0.0, kWall));
  add(Vec3(kWall, outer, 0.5 * kHeight), Vec3(outer, 0.0, wall_z));
  add(Vec3(kWall, outer, 0.5 * kHeight), Vec3(-outer, 0.0, wall_z));
  add(Vec3(kInside, kWall, 0.5 * kHeight), Vec3(0.0, outer, wall_z));
  add(Vec3(kInside, kWall, 0.5 * kHeight), Vec3(0.0, -outer, wall_z));
  if (!as_colliders) {
    bin.mass = 50.0;
    scene.bin = *world.addBody(bin);
    scene.bin_z = world.bodies().position(*world.bodies().find(scene.bin)).z();
  }
  std::mt19937 rng(seed);
  std::uniform_real_distribution<Real> jitter(-0.005, 0.005);
  constexpr int kSide = 18;
  for (int i = 0; i < grains; ++i) {
    const int x = i % kSide;
    const int y = (i / kSide) % kSide;
    const int k = i / (kSide * kSide);
    ParticleSpec grain;
    grain.position = Vec3(-0.51 + 0.06 * x + jitter(rng), -0.51 + 0.06 * y + jitter(rng),
                          0.4 + 0.06 * k + jitter(rng));
    grain.inverse_mass = 1.0 / kGrainMass;
    grain.radius = kGrainRadius;
    world.addParticle(grain);
  }
  return scene;
}

// Grains whose centre is outside the bin's inner walls.
inline int grainsOutside(const World& world) {
  const auto x = world.particles().positions();
  int outside = 0;
  for (Eigen::Index i = 0; i < x.cols(); ++i) {
    outside += std::abs(x(0, i)) > kInside || std::abs(x(1, i)) > kInside;
  }
  return outside;
}

// The deepest overlap of a grain with the bin body now (0 with none).
inline Real deepestGrainInBin(const World& world) {
  Real deepest = 0.0;
  for (const BodyContactReport& contact : world.bodyContacts()) {
    if (contact.other != BodyContactReport::Other::kParticle) continue;
    for (const auto& point : contact.points) deepest = std::max(deepest, -point.separation);
  }
  return deepest;
}

}  // namespace grain_bin
}  // namespace engine
}  // namespace mass_aggregate_sim
