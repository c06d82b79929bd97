// Where a pyramid's kinetic energy is with sleeping off (docs/BENCHMARKS.md, 2026-11-28 session
// 17): each second (and each of the last five frames) the total and the four liveliest boxes,
// their velocities and where they are. Build and run from the repository root after
// scripts/bench.sh has built the engine:
//   g++ -std=c++17 -O2 -I include -I bench/rigid -I /usr/include/eigen3 \
//     docs/benchmarks/pyramid_ke_probe.cpp bench/rigid/rigid_scenes.cpp -o /tmp/pyramid_ke_probe \
//     -L ~/mass_aggregate_sim_ws/devel/lib -lmass_aggregate_sim_engine \
//     -Wl,-rpath,$HOME/mass_aggregate_sim_ws/devel/lib
//   /tmp/pyramid_ke_probe 20 4 2              # base, substeps, iterations
//   NOSHOCK=1 /tmp/pyramid_ke_probe 20 4 2    # also NOGUESS, RELAX=n, HZ=x, FRAMES=n, and
//                                             # GUESSFROM=f / GUESSUNTIL=f: load guesses only
//                                             # from frame f on / before frame f (session 18)
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <utility>
#include <vector>

#include "engine_scene.h"
#include "mass_aggregate_sim/engine/world/world.h"
using namespace mass_aggregate_sim;
using engine::Vec3;
int main(int argc, char** argv) {
  const int base = argc > 1 ? atoi(argv[1]) : 20;
  engine::BodySettings settings;
  settings.substeps = argc > 2 ? atoi(argv[2]) : 4;
  settings.iterations = argc > 3 ? atoi(argv[3]) : 2;
  settings.sleep = false;
  if (getenv("RELAX")) settings.relax_iterations = atoi(getenv("RELAX"));
  if (getenv("HZ")) settings.contact_hertz = atof(getenv("HZ"));
  if (getenv("NOSHOCK")) settings.shock_propagation = false;
  if (getenv("NOGUESS")) settings.guess_loads = false;
  const int frames = getenv("FRAMES") ? atoi(getenv("FRAMES")) : 600;
  engine::World world = bench::rigid::engineWorld(bench::rigid::pyramid(base), settings);
  const auto& bodies = world.bodies();
  const int guess_from = getenv("GUESSFROM") ? atoi(getenv("GUESSFROM")) : 0;
  const int guess_until = getenv("GUESSUNTIL") ? atoi(getenv("GUESSUNTIL")) : 1 << 30;
  for (int f = 0; f < frames; ++f) {
    engine::BodySettings now = world.bodySettings();
    now.guess_loads = settings.guess_loads && f >= guess_from && f < guess_until;
    world.setBodySettings(now);
    world.step();
    if (f % 60 != 59 && f < frames - 5) continue;
    std::vector<std::pair<double, std::size_t>> energies;
    double total = 0.0;
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      if (!bodies.dynamic(i)) continue;
      const Vec3 w_body = bodies.orientation(i).conjugate() * bodies.angularVelocity(i);
      const double e = 0.5 * bodies.linearVelocity(i).squaredNorm() / bodies.inverseMass(i) +
                       0.5 * w_body.dot(bodies.principalInertia(i).cwiseProduct(w_body));
      total += e;
      energies.emplace_back(e, i);
    }
    std::sort(energies.rbegin(), energies.rend());
    std::printf("frame %d: KE %.3g J; liveliest:", f + 1, total);
    for (std::size_t k = 0; k < std::min<std::size_t>(4, energies.size()); ++k) {
      const std::size_t i = energies[k].second;
      const Vec3 p = bodies.position(i);
      const Vec3 v = bodies.linearVelocity(i);
      const Vec3 w = bodies.angularVelocity(i);
      std::printf(" [%.2g J at (%.2f %.2f %.2f) v (%.3f %.3f %.3f) w (%.3f %.3f %.3f)]",
                  energies[k].first, p.x(), p.y(), p.z(), v.x(), v.y(), v.z(), w.x(), w.y(), w.z());
    }
    std::printf("\n");
  }
}
