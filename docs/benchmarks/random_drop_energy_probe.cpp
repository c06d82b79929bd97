// The 1,000-box random drop (sleeping on, 4 x 2): over frames FROM to TO, the sum of the
// world's rises in mechanical energy (kinetic + m g z of every dynamic body) from one frame to
// the next, and how many frames one body gained more than THRESHOLD J (VERBOSE prints them).
// Contacts with restitution 0 and friction only take energy out, so a rise means the solver
// pushed (docs/BENCHMARKS.md, 2026-11-28 session 21). Build from the repository root after
// scripts/bench.sh has built the engine:
//   g++ -std=c++17 -O2 -I include -I bench/rigid -I /usr/include/eigen3 \
//     docs/benchmarks/random_drop_energy_probe.cpp bench/rigid/rigid_scenes.cpp \
//     -o /tmp/random_drop_energy_probe -L ~/mass_aggregate_sim_ws/devel/lib \
//     -lmass_aggregate_sim_engine -Wl,-rpath,$HOME/mass_aggregate_sim_ws/devel/lib
//   SEED=3 /tmp/random_drop_energy_probe 600 1200 1e-3
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "engine_scene.h"
#include "mass_aggregate_sim/engine/world/world.h"
using namespace mass_aggregate_sim;
int main(int argc, char** argv) {
  const int from = atoi(argv[1]), to = atoi(argv[2]);
  const double thresh = argc > 3 ? atof(argv[3]) : 1e-3;
  const std::uint64_t seed = getenv("SEED") ? std::strtoull(getenv("SEED"), nullptr, 10) : 1;
  engine::BodySettings settings;
  settings.sleep = true;
  engine::World world = bench::rigid::engineWorld(bench::rigid::randomDrop(1000, seed), settings);
  const auto& b = world.bodies();
  auto energy = [&](std::size_t i) {
    return 0.5 * b.mass(i) * b.linearVelocity(i).squaredNorm() +
           0.5 *
               b.angularVelocity(i).dot(b.worldInverseInertia(i).inverse() * b.angularVelocity(i)) +
           b.mass(i) * 9.81 * b.position(i).z();
  };
  std::vector<double> e(b.size());
  double total_rise = 0;
  int events = 0;
  for (int f = 0; f < to; ++f) {
    if (f >= from)
      for (std::size_t i = 0; i < b.size(); ++i) e[i] = energy(i);
    world.step();
    if (f < from) continue;
    double world_de = 0, top = 0;
    std::size_t ti = 0;
    for (std::size_t i = 0; i < b.size(); ++i) {
      if (!b.dynamic(i)) continue;
      const double d = energy(i) - e[i];
      world_de += d;
      if (d > top) {
        top = d;
        ti = i;
      }
    }
    if (world_de > 0) total_rise += world_de;
    if (top > thresh) {
      ++events;
      if (getenv("VERBOSE"))
        std::printf(
            "f %d world dE %.3g J top body %zu dE %.3g J (mass %.3f v %.3f w %.3f z %.3f)\n", f + 1,
            world_de, ti, top, b.mass(ti), b.linearVelocity(ti).norm(),
            b.angularVelocity(ti).norm(), b.position(ti).z());
    }
  }
  std::printf("seed %llu frames %d-%d: world energy rises sum %.4g J, body rises > %.3g J: %d\n",
              (unsigned long long)seed, from, to, total_rise, thresh, events);
}
