// How long the 1,000-box random drop takes to fall asleep as a whole, with sleeping on (the
// default a user has), and what it rests like then (docs/BENCHMARKS.md, 2026-11-28 session 20).
// Prints one line per run: the time when every box sleeps (99 if not within the frames), the
// deepest overlap then, and the kinetic energy and deepest overlap at 10 s. Build and run from the
// repository root after scripts/bench.sh has built the engine:
//   g++ -std=c++17 -O2 -I include -I bench/rigid -I /usr/include/eigen3 \
//     docs/benchmarks/random_drop_sleep_probe.cpp bench/rigid/rigid_scenes.cpp \
//     -o /tmp/random_drop_sleep_probe -L ~/mass_aggregate_sim_ws/devel/lib \
//     -lmass_aggregate_sim_engine -Wl,-rpath,$HOME/mass_aggregate_sim_ws/devel/lib
//   for s in $(seq 1 100); do SEED=$s /tmp/random_drop_sleep_probe 1800; done
// Environment: SEED=n the scene's seed (1 by default), LEVER=x min_twist_lever, VERBOSE=1 every
// half second the awake boxes faster than the sleep speed and the fastest one.
#include <algorithm>
#include <cstdio>
#include <cstdlib>

#include "engine_scene.h"
#include "mass_aggregate_sim/engine/world/world.h"
using namespace mass_aggregate_sim;

double deepestOverlap(const engine::World& world) {
  double deepest = 0.0;
  for (const auto& c : world.bodyContacts()) {
    for (const auto& p : c.points) deepest = std::max(deepest, -p.separation);
  }
  return deepest;
}

int main(int argc, char** argv) {
  const int frames = argc > 1 ? atoi(argv[1]) : 1800;
  const std::uint64_t seed = getenv("SEED") ? std::strtoull(getenv("SEED"), nullptr, 10) : 1;
  engine::BodySettings settings;
  settings.sleep = true;
  if (getenv("LEVER")) settings.min_twist_lever = atof(getenv("LEVER"));
  engine::World world = bench::rigid::engineWorld(bench::rigid::randomDrop(1000, seed), settings);
  int all_asleep = -1;
  double ke10 = 0.0, deep10 = 0.0, deep_then = 0.0;
  for (int f = 0; f < frames; ++f) {
    world.step();
    const auto& b = world.bodies();
    int asleep = 0, dynamic = 0, fast = 0;
    double top = 0.0;
    std::size_t top_index = 0;
    for (std::size_t i = 0; i < b.size(); ++i) {
      if (!b.dynamic(i)) continue;
      ++dynamic;
      if (!b.awake(i)) {
        ++asleep;
        continue;
      }
      // The sleep test's speed: no point of the body faster than this.
      const double speed = b.linearVelocity(i).norm() + b.angularVelocity(i).norm() * b.reach(i);
      if (speed >= settings.sleep_speed) ++fast;
      if (speed > top) {
        top = speed;
        top_index = i;
      }
    }
    if (f == 599) {
      ke10 = world.kineticEnergy();
      deep10 = deepestOverlap(world);
    }
    if (asleep == dynamic && all_asleep < 0) {
      all_asleep = f + 1;
      deep_then = deepestOverlap(world);
      if (f >= 599) break;
    }
    if (getenv("VERBOSE") && f % 30 == 29 && asleep < dynamic) {
      std::printf("t %.1f fast %d top %.3f m/s (v %.3f w %.3f reach %.3f mass %.3f) body %zu\n",
                  (f + 1) / 60.0, fast, top, b.linearVelocity(top_index).norm(),
                  b.angularVelocity(top_index).norm(), b.reach(top_index), b.mass(top_index),
                  top_index);
    }
  }
  std::printf("seed %llu asleep_s %.2f deepest_then_mm %.2f ke10 %.3g deep10_mm %.2f\n",
              static_cast<unsigned long long>(seed), all_asleep < 0 ? 99.0 : all_asleep / 60.0,
              1e3 * deep_then, ke10, 1e3 * deep10);
}
