#pragma once
// The dense drop of issue 13, shared by its engine test (test/engine/world/dense_drop_test.cpp) and
// its benchmark (bench/dense_drop_bench.cpp), so both run the same scene: 8,000 spheres of r = 3 cm
// and 0.1 kg (friction 0.3, restitution 0.2) in a 20 x 20 x 20 block, 9 cm apart across and
// 20 cm apart in height from 0.2 m to 4 m, fall into a box 2 m wide made of five half-spaces
// (the same material), default config (dt = 1/60 s, one substep) with gravity along -z. The last
// layers arrive at 8.5 m/s, more than twice a sphere's diameter per step, onto a pile that is
// already there.

#include <cstddef>
#include <random>

#include "mass_aggregate_sim/engine/world/world.h"

namespace mass_aggregate_sim {
namespace engine {
namespace dense_drop {

constexpr int kPerSide = 20;
constexpr int kLayers = 20;
constexpr Real kRadius = 0.03;
constexpr Real kHalfWidth = 1.0;  // the box spans [-1, 1] m in x and y, the floor is z = 0
constexpr Real kSpacing = 0.09;
constexpr Real kLowest = 0.2;
constexpr Real kHighest = 4.0;
constexpr int kStepsPerSecond = 60;

inline World makeWorld() {
  WorldConfig config;
  config.gravity = Vec3(0.0, 0.0, -9.81);
  World world(config);
  CollisionSettings settings;
  settings.particle_collisions = true;
  settings.broadphase = Broadphase::kUniformGrid;
  settings.particle_restitution = 0.2;
  settings.particle_friction = 0.3;
  world.setCollisionSettings(settings);
  const Material material{0.2, 0.3};
  world.addCollider(PlaneCollider{Vec3::UnitZ(), 0.0, material});
  world.addCollider(PlaneCollider{Vec3::UnitX(), -kHalfWidth, material});
  world.addCollider(PlaneCollider{-Vec3::UnitX(), -kHalfWidth, material});
  world.addCollider(PlaneCollider{Vec3::UnitY(), -kHalfWidth, material});
  world.addCollider(PlaneCollider{-Vec3::UnitY(), -kHalfWidth, material});
  std::mt19937 rng(7);
  std::uniform_real_distribution<Real> jitter(-0.005, 0.005);
  const Real first = -0.5 * kSpacing * (kPerSide - 1);
  const Real rise = (kHighest - kLowest) / (kLayers - 1);
  for (int k = 0; k < kLayers; ++k) {
    for (int j = 0; j < kPerSide; ++j) {
      for (int i = 0; i < kPerSide; ++i) {
        ParticleSpec spec;
        spec.position = Vec3(first + kSpacing * i + jitter(rng), first + kSpacing * j + jitter(rng),
                             kLowest + rise * k + jitter(rng));
        spec.radius = kRadius;
        spec.inverse_mass = 10.0;
        world.addParticle(spec);
      }
    }
  }
  return world;
}

// Spheres whose centre is not inside the box (beyond a wall or under the floor).
inline std::size_t spheresOutside(const World& world) {
  const auto x = world.particles().positions();
  std::size_t outside = 0;
  for (Eigen::Index i = 0; i < x.cols(); ++i) {
    if (!(x(0, i) > -kHalfWidth && x(0, i) < kHalfWidth && x(1, i) > -kHalfWidth &&
          x(1, i) < kHalfWidth && x(2, i) > 0.0)) {
      ++outside;
    }
  }
  return outside;
}

}  // namespace dense_drop
}  // namespace engine
}  // namespace mass_aggregate_sim
