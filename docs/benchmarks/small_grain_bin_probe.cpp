// The bin of BodySleep.APileInABinThatFallsAsleepSettlesOnTheLongerSubstep (docs/BENCHMARKS.md,
// 2026-11-29 session 31): 432 grains of 2.5 cm and 20 g dropped into a 20 kg bin 0.5 m square
// inside, 60 Hz, followed for 30 s: every half second whether the bin is awake, the fastest grain
// (its index and height) and the particle solver's velocity passes in the last substep; then the
// step the bin fell asleep in and how far the grains moved from 10 s to 30 s. NOSLEEP=1 keeps the
// bin awake; TOL sets the particle solver's velocity_tolerance; JIT and FREQ the block's jitter
// (0.002 m times sin(1.7 k) for grain k, as the test). Build and run from the repository root
// after scripts/bench.sh has built the engine:
//   g++ -std=c++17 -O2 -I include -I /usr/include/eigen3 \
//     docs/benchmarks/small_grain_bin_probe.cpp -o /tmp/small_grain_bin_probe \
//     -L ~/mass_aggregate_sim_ws/devel/lib -lmass_aggregate_sim_engine \
//     -Wl,-rpath,$HOME/mass_aggregate_sim_ws/devel/lib
//   /tmp/small_grain_bin_probe
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "mass_aggregate_sim/engine/world/world.h"
using namespace mass_aggregate_sim::engine;
int main() {
  WorldConfig config;
  config.dt = 1.0 / 60.0;
  config.gravity = Vec3(0.0, 0.0, -9.81);
  World world(config);
  PlaneCollider ground;
  ground.material = Material{0.1, 0.6};
  world.addCollider(ground);
  CollisionSettings collisions;
  collisions.particle_collisions = true;
  collisions.particle_restitution = 0.1;
  collisions.particle_friction = 0.3;
  if (getenv("TOL")) collisions.velocity_tolerance = atof(getenv("TOL"));
  world.setCollisionSettings(collisions);
  BodySpec bin;
  bin.mass = 20.0;
  const auto add = [&](const Vec3& half_extents, const Vec3& at) {
    BodyShapeSpec shape;
    shape.geometry = BoxShape{half_extents};
    shape.material = Material{0.0, 0.6};
    shape.local.position = at;
    bin.shapes.push_back(shape);
  };
  const Real inside = 0.25, wall = 0.05, outer = inside + wall;
  add(Vec3(outer, outer, wall), Vec3(0.0, 0.0, wall));
  add(Vec3(wall, outer, 0.2), Vec3(outer, 0.0, 2.0 * wall + 0.2));
  add(Vec3(wall, outer, 0.2), Vec3(-outer, 0.0, 2.0 * wall + 0.2));
  add(Vec3(inside, wall, 0.2), Vec3(0.0, outer, 2.0 * wall + 0.2));
  add(Vec3(inside, wall, 0.2), Vec3(0.0, -outer, 2.0 * wall + 0.2));
  const BodyId id = *world.addBody(bin);
  if (getenv("NOSLEEP")) {
    BodySettings settings = world.bodySettings();
    settings.sleep = false;
    world.setBodySettings(settings);
  }
  const Real r = 0.025;
  const Real amplitude = getenv("JIT") ? atof(getenv("JIT")) : 0.002;
  const Real frequency = getenv("FREQ") ? atof(getenv("FREQ")) : 1.7;
  ParticleSpec grain;
  grain.radius = r;
  grain.inverse_mass = 50.0;
  for (int k = 0; k < 12 * 12 * 3; ++k) {
    const int i = k % 12, j = (k / 12) % 12, l = k / 144;
    const Real jitter = amplitude * std::sin(frequency * k);
    grain.position =
        Vec3(-inside + r + 0.041 * i + jitter, -inside + r + 0.041 * j - jitter, 0.15 + 0.055 * l);
    world.addParticle(grain);
  }
  int slept = -1;
  Eigen::Matrix3Xd at_10s;
  for (int s = 0; s < 30 * 60; ++s) {
    if (s == 10 * 60) at_10s = world.particles().positions();
    world.step();
    const bool awake = world.bodies().awake(*world.bodies().find(id));
    if (!awake && slept < 0) slept = s;
    if (s % 30 != 29) continue;
    Eigen::Index g = 0;
    const double fastest = world.particles().velocities().colwise().norm().maxCoeff(&g);
    std::printf("t %.1f s: bin awake %d, fastest grain %.2e m/s (#%ld at z %.4f m), %d passes\n",
                (s + 1) / 60.0, static_cast<int>(awake), fastest, static_cast<long>(g),
                world.particles().positions()(2, g), world.lastContactStats().velocity_iterations);
  }
  Eigen::Index farthest = 0;
  const Eigen::VectorXd moved = (world.particles().positions() - at_10s).colwise().norm();
  const double most = moved.maxCoeff(&farthest);
  std::printf(
      "bin asleep from step %d; from 10 s to 30 s the farthest grain moved %.3e m (#%ld), %ld "
      "grains more than 10 um\n",
      slept, most, static_cast<long>(farthest), static_cast<long>((moved.array() > 1e-5).count()));
}
