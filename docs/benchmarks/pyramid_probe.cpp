// Why the 5,050-box pyramid at the default 4 x 2 never sleeps (docs/BENCHMARKS.md, 2026-11-26):
// each simulated second, the fastest point speed |v| + |w| r of any box and how many boxes are
// above the sleep speed (0.05 m/s). Build and run from the repository root after
// scripts/bench.sh has built the engine (53 s a run):
//   g++ -std=c++17 -O2 -I include -I bench/rigid -I /usr/include/eigen3 \
//     docs/benchmarks/pyramid_probe.cpp bench/rigid/rigid_scenes.cpp -o /tmp/pyramid_probe \
//     -L ~/mass_aggregate_sim_ws/devel/lib -lmass_aggregate_sim_engine \
//     -Wl,-rpath,$HOME/mass_aggregate_sim_ws/devel/lib
//   /tmp/pyramid_probe 100 4 2            # base, substeps, iterations
//   RELAX=1 /tmp/pyramid_probe 100 4 2    # also RELAX, HZ, ZETA, PUSH: BodySettings fields
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "engine_scene.h"
#include "mass_aggregate_sim/engine/world/world.h"
using namespace mass_aggregate_sim;
using engine::Vec3;
int main(int argc, char** argv) {
  const int base = argc > 1 ? atoi(argv[1]) : 100;
  const int substeps = argc > 2 ? atoi(argv[2]) : 4;
  const int iterations = argc > 3 ? atoi(argv[3]) : 2;
  const auto scene = bench::rigid::pyramid(base);
  engine::BodySettings settings;
  settings.substeps = substeps;
  settings.iterations = iterations;
  if (getenv("RELAX")) settings.relax_iterations = atoi(getenv("RELAX"));
  if (getenv("HZ")) settings.contact_hertz = atof(getenv("HZ"));
  if (getenv("ZETA")) settings.contact_damping_ratio = atof(getenv("ZETA"));
  if (getenv("PUSH")) settings.max_push_speed = atof(getenv("PUSH"));
  engine::World world = bench::rigid::engineWorld(scene, settings);
  const auto& bodies = world.bodies();
  for (int f = 0; f < 600; ++f) {
    world.step();
    if (f % 60 == 59) {
      double worst = 0;
      std::size_t at = 0;
      int fast = 0, awake = 0;
      for (std::size_t i = 0; i < bodies.size(); ++i) {
        const double s =
            bodies.linearVelocity(i).norm() + bodies.angularVelocity(i).norm() * bodies.reach(i);
        if (s > worst) {
          worst = s;
          at = i;
        }
        if (s > 0.05) ++fast;
        if (bodies.awake(i)) ++awake;
      }
      const Vec3 p = bodies.position(at);
      std::printf(
          "t %2.0f s: awake %d, point speed max %.4f m/s at (%.1f, %.1f, %.1f) v %.4f w %.4f; %d "
          "above 0.05\n",
          (f + 1) / 60.0, awake, worst, p.x(), p.y(), p.z(), bodies.linearVelocity(at).norm(),
          bodies.angularVelocity(at).norm(), fast);
    }
  }
}
