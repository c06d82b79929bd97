// Grains poured into a bin (docs/BENCHMARKS.md, 2026-11-29 session 27): a dynamic open box of
// five boxes (floor 1.3 m square and 10 cm thick, walls 60 cm high, 50 kg) on the ground, N grains
// of 2.5 cm radius and 20 g (friction 0.3, restitution 0.1) dropped from a loose block 18 x 18
// grains wide, 6 cm apart, from 0.4 m up. 60 Hz, the default body settings (4 substeps, 2
// iterations). Prints each second's mean cost of a step with the bin's height and orientation, then
// the grains' kinetic energy, the bin's speed and height, the grain-bin contacts, the deepest
// grain-bin overlap over the last 2 s and how many grains ended outside the bin's walls.
// Arguments: N (2000) and the seconds (6); SEED sets the block's jitter (1). Build and run from the
// repository root after scripts/bench.sh has built the engine:
//   g++ -std=c++17 -O2 -I include -I /usr/include/eigen3 \
//     docs/benchmarks/grain_bin_probe.cpp -o /tmp/grain_bin_probe \
//     -L ~/mass_aggregate_sim_ws/devel/lib -lmass_aggregate_sim_engine \
//     -Wl,-rpath,$HOME/mass_aggregate_sim_ws/devel/lib
//   /tmp/grain_bin_probe 4000 6
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>

#include "mass_aggregate_sim/engine/world/world.h"
using namespace mass_aggregate_sim::engine;
int main(int argc, char** argv) {
  const int n = argc > 1 ? atoi(argv[1]) : 2000;
  const int seconds = argc > 2 ? atoi(argv[2]) : 6;
  const int hz = 60;
  WorldConfig c;
  c.dt = 1.0 / hz;
  c.gravity = Vec3(0, 0, -9.81);
  World world(c);
  CollisionSettings cs;
  cs.particle_collisions = true;
  cs.broadphase = Broadphase::kUniformGrid;
  cs.particle_restitution = 0.1;
  cs.particle_friction = 0.3;
  world.setCollisionSettings(cs);
  world.addCollider(PlaneCollider{Vec3::UnitZ(), 0.0, Material{0.1, 0.6}});
  BodySpec bin;
  const Real half = 0.6, wall = 0.05, height = 0.6;
  const auto add = [&](const Vec3& half_extents, const Vec3& at) {
    BodyShapeSpec s;
    s.geometry = BoxShape{half_extents};
    s.material = Material{0.0, 0.6};
    s.local.position = at;
    bin.shapes.push_back(s);
  };
  add(Vec3(half + wall, half + wall, wall), Vec3(0, 0, wall));
  add(Vec3(wall, half + wall, height / 2), Vec3(half + wall, 0, 2 * wall + height / 2));
  add(Vec3(wall, half + wall, height / 2), Vec3(-half - wall, 0, 2 * wall + height / 2));
  add(Vec3(half, wall, height / 2), Vec3(0, half + wall, 2 * wall + height / 2));
  add(Vec3(half, wall, height / 2), Vec3(0, -half - wall, 2 * wall + height / 2));
  bin.mass = 50;
  const BodyId id = *world.addBody(bin);
  std::mt19937 rng(getenv("SEED") ? atoi(getenv("SEED")) : 1);
  std::uniform_real_distribution<Real> jitter(-0.005, 0.005);
  const int side = 18;
  for (int i = 0; i < n; ++i) {
    const int x = i % side, y = (i / side) % side, k = i / (side * side);
    ParticleSpec p;
    p.position = Vec3(-0.51 + 0.06 * x + jitter(rng), -0.51 + 0.06 * y + jitter(rng),
                      0.4 + 0.06 * k + jitter(rng));
    p.inverse_mass = 50.0;
    p.radius = 0.025;
    world.addParticle(p);
  }
  const int steps = seconds * hz, late = 2 * hz;
  double second = 0.0, late_deepest = 0.0;
  for (int s = 0; s < steps; ++s) {
    const auto t0 = std::chrono::steady_clock::now();
    world.step();
    second += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if ((s + 1) % hz == 0) {
      const std::size_t b = *world.bodies().find(id);
      const Quat q = world.bodies().orientation(b);
      std::printf("%.2f ms [z %.3f q %.3f %.3f %.3f %.3f] ", 1e3 * second / hz,
                  world.bodies().position(b).z(), q.w(), q.x(), q.y(), q.z());
      second = 0.0;
    }
    if (s >= steps - late) {
      for (const auto& r : world.bodyContacts()) {
        if (r.other != BodyContactReport::Other::kParticle) continue;
        for (const auto& p : r.points) late_deepest = std::max(late_deepest, -p.separation);
      }
    }
  }
  const auto v = world.particles().velocities();
  const auto x = world.particles().positions();
  double ke = 0.0;
  int outside = 0, on_bin = 0;
  for (Eigen::Index i = 0; i < v.cols(); ++i) {
    ke += 0.5 * 0.02 * v.col(i).squaredNorm();
    outside += std::abs(x(0, i)) > half || std::abs(x(1, i)) > half;
  }
  for (const auto& r : world.bodyContacts())
    on_bin += r.other == BodyContactReport::Other::kParticle;
  const std::size_t b = *world.bodies().find(id);
  std::printf(
      "| grains KE %.3e J, bin at %.2e m/s, z %.5f (0.27386 at rest), grain-bin contacts %d, "
      "deepest over the last 2 s %.2f mm, grains outside %d\n",
      ke, world.bodies().linearVelocity(b).norm(), world.bodies().position(b).z(), on_bin,
      1e3 * late_deepest, outside);
}
