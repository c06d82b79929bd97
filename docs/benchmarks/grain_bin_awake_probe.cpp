// Grains poured into a bin (docs/BENCHMARKS.md, 2026-11-29 session 31): bench/grain_bin_scene.h,
// the bin a dynamic body (or, with COLL=1, the same bin of static colliders), followed from the
// pour until it has rested a while. Prints every half second the mean cost of a step and the
// particle solver's velocity passes in the last substep (both over the half second), whether the
// bin is awake, the grains' contacts, mean and highest centre, kinetic energy and fastest speed,
// the deepest grain-bin overlap, the largest overlap the particle solver left, the grains
// outside, and the bin's height from rest; then the whole run's cost, the step from which the bin
// slept, and how far the grains moved over the last 4 s. Arguments: N (4000), the seconds (8),
// the block's jitter seed (1). Build and run from the repository root after scripts/bench.sh has
// built the engine:
//   g++ -std=c++17 -O2 -I include -I /usr/include/eigen3 \
//     docs/benchmarks/grain_bin_awake_probe.cpp -o /tmp/grain_bin_awake_probe \
//     -L ~/mass_aggregate_sim_ws/devel/lib -lmass_aggregate_sim_engine \
//     -Wl,-rpath,$HOME/mass_aggregate_sim_ws/devel/lib
//   /tmp/grain_bin_awake_probe 4000 8
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>

#include "../../bench/grain_bin_scene.h"
using namespace mass_aggregate_sim::engine;
int main(int argc, char** argv) {
  const int n = argc > 1 ? atoi(argv[1]) : 4000;
  const int seconds = argc > 2 ? atoi(argv[2]) : 8;
  const unsigned seed = argc > 3 ? static_cast<unsigned>(atoi(argv[3])) : 1;
  grain_bin::Scene scene = grain_bin::makeScene(n, getenv("COLL") != nullptr, seed);
  World& world = scene.world;
  const bool has_bin = !world.bodies().empty();
  const int hz = grain_bin::kStepsPerSecond;
  double period_ms = 0.0, total_ms = 0.0, worst_overlap = 0.0;
  int passes = 0, steps = 0, asleep_from = -1;
  Eigen::Matrix3Xd before_last;
  for (int s = 0; s < seconds * hz; ++s) {
    if (s == std::max(0, seconds - 4) * hz) before_last = world.particles().positions();
    const auto start = std::chrono::steady_clock::now();
    world.step();
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    period_ms += ms;
    total_ms += ms;
    ++steps;
    passes += world.lastContactStats().velocity_iterations;
    worst_overlap = std::max<double>(worst_overlap, world.lastContactStats().max_penetration);
    const bool awake = has_bin && world.bodies().awake(0);
    if (has_bin && !awake && asleep_from < 0) asleep_from = s;
    if (awake) asleep_from = -1;
    if (s % (hz / 2) != hz / 2 - 1) continue;
    const auto x = world.particles().positions();
    const auto v = world.particles().velocities();
    double z_sum = 0.0, z_max = 0.0, ke = 0.0, fastest = 0.0;
    for (Eigen::Index i = 0; i < x.cols(); ++i) {
      z_sum += x(2, i);
      z_max = std::max<double>(z_max, x(2, i));
      ke += 0.5 * grain_bin::kGrainMass * v.col(i).squaredNorm();
      fastest = std::max<double>(fastest, v.col(i).norm());
    }
    std::printf(
        "t %.1f s: %.2f ms/step, %.1f velocity passes, bin awake %d | contacts %zu, z mean %.4f "
        "max %.4f m, KE %.3e J, fastest %.4f m/s, grain-bin overlap %.5f m, overlap left %.5f m, "
        "outside %d, bin height %.6f m\n",
        (s + 1) / static_cast<double>(hz), period_ms / steps, passes / static_cast<double>(steps),
        has_bin ? static_cast<int>(awake) : -1, world.lastContactStats().contacts,
        z_sum / static_cast<double>(x.cols()), z_max, ke, fastest,
        grain_bin::deepestGrainInBin(world), worst_overlap, grain_bin::grainsOutside(world),
        has_bin ? world.bodies().position(0).z() - scene.bin_z : 0.0);
    period_ms = 0.0;
    worst_overlap = 0.0;
    passes = 0;
    steps = 0;
  }
  Eigen::Index farthest = 0;
  const Eigen::VectorXd moved = (world.particles().positions() - before_last).colwise().norm();
  const double most = moved.maxCoeff(&farthest);
  std::printf(
      "total %.1f ms, bin asleep from step %d; over the last 4 s the farthest grain moved %.3e m "
      "(#%ld), %ld grains more than 10 um\n",
      total_ms, asleep_from, most, static_cast<long>(farthest),
      static_cast<long>((moved.array() > 1e-5).count()));
}
