// Grains poured into a bin (docs/BENCHMARKS.md, 2026-11-29 session 27): bench/grain_bin_scene.h
// with the bin a dynamic body, followed frame by frame. Prints each second's mean cost of a step
// with the bin's height and orientation, then the grains' kinetic energy, the bin's speed and
// height, the grain-bin contacts, the deepest grain-bin overlap over the last 2 s and how many
// grains ended outside the bin's walls. Arguments: N (2000) and the seconds (6); SEED sets the
// block's jitter (1). Build and run from the repository root after scripts/bench.sh has built the
// engine:
//   g++ -std=c++17 -O2 -I include -I /usr/include/eigen3 \
//     docs/benchmarks/grain_bin_probe.cpp -o /tmp/grain_bin_probe \
//     -L ~/mass_aggregate_sim_ws/devel/lib -lmass_aggregate_sim_engine \
//     -Wl,-rpath,$HOME/mass_aggregate_sim_ws/devel/lib
//   /tmp/grain_bin_probe 4000 6
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>

#include "../../bench/grain_bin_scene.h"
using namespace mass_aggregate_sim::engine;
int main(int argc, char** argv) {
  const int n = argc > 1 ? atoi(argv[1]) : 2000;
  const int seconds = argc > 2 ? atoi(argv[2]) : 6;
  const int hz = grain_bin::kStepsPerSecond;
  grain_bin::Scene scene =
      grain_bin::makeScene(n, false, getenv("SEED") ? atoi(getenv("SEED")) : 1);
  World& world = scene.world;
  const BodyId id = scene.bin;
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
    if (s >= steps - late)
      late_deepest = std::max(late_deepest, grain_bin::deepestGrainInBin(world));
  }
  const auto v = world.particles().velocities();
  double ke = 0.0;
  for (Eigen::Index i = 0; i < v.cols(); ++i)
    ke += 0.5 * grain_bin::kGrainMass * v.col(i).squaredNorm();
  int on_bin = 0;
  for (const auto& r : world.bodyContacts())
    on_bin += r.other == BodyContactReport::Other::kParticle;
  const std::size_t b = *world.bodies().find(id);
  std::printf(
      "| grains KE %.3e J, bin at %.2e m/s, z %.5f (%.5f at rest), grain-bin contacts %d, "
      "deepest over the last 2 s %.2f mm, grains outside %d\n",
      ke, world.bodies().linearVelocity(b).norm(), world.bodies().position(b).z(), scene.bin_z,
      on_bin, 1e3 * late_deepest, grain_bin::grainsOutside(world));
}
