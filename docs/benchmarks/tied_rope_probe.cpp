// A rope tied between two points (docs/BENCHMARKS.md and README, session 35): 20 rods of 5 cm
// (1 m, 1 kg) between anchors SPAN apart, released as a V of exact lengths (down to the middle at
// the angle acos(SPAN), then up), 20 s at 60 Hz. Prints every 5 s the energy against the start
// (and the most it rose above it), the kinetic energy, the worst strain of a rod and the position
// passes of the last step. Build and run from the repository root after scripts/bench.sh has
// built the engine:
//   g++ -std=c++17 -O2 -I include -I /usr/include/eigen3 docs/benchmarks/tied_rope_probe.cpp \
//     -o /tmp/tied_rope_probe -L ~/mass_aggregate_sim_ws/devel/lib -lmass_aggregate_sim_engine \
//     -Wl,-rpath,$HOME/mass_aggregate_sim_ws/devel/lib
//   for s in 0.999 0.99 0.95 0.8 0.5; do /tmp/tied_rope_probe 20 $s 1; done
// Arguments: RODS SPAN SUBSTEPS [SECONDS]. The last line of each run on 2026-11-30, by engine:
//   span   257545a (row by row)                  2c6dfa8 (chains, Newton)             this fix
//   0.999  -0.75 J (most -0.013), 13 % strain    +1.7 J (most +3.1), 2.8 %          -0.72 J (most
//   -0.013), 4.9 % 0.99   -0.59 J (most -0.013), 16 %           +1.4 J (most +1.5), 5e-14 -0.54 J
//   (most -0.013), 4.5 % 0.95   -0.39 J (most -0.012), 10 %           +0.21 J (most +0.21), 2e-15
//   -0.35 J (most -0.013), 3.5 % 0.8    -0.26 J (most -0.011), 7.3 %          -0.05 J (most +0.07),
//   2e-13        -0.24 J (most -0.012), 2.2 % 0.5    -0.16 J (most -0.010), 5.8 %          +0.09 J
//   (most +0.13), 2e-10        -0.14 J (most -0.012), 1.8 %
// Kinetic energy at 20 s: row by row 1.6e-4 to 2.0e-2 J, chains 8.2e-3 to 2.1 J, this fix 3.2e-4 to
// 2.0e-3 J.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "mass_aggregate_sim/engine/world/world.h"

using namespace mass_aggregate_sim::engine;

int main(int argc, char** argv) {
  if (argc < 4) {
    std::fprintf(stderr, "usage: %s RODS SPAN SUBSTEPS [SECONDS]\n", argv[0]);
    return 2;
  }
  const int rods = std::atoi(argv[1]);
  const double span = std::atof(argv[2]);
  WorldConfig config;
  config.gravity = Vec3(0, 0, -9.81);
  config.substeps = std::atoi(argv[3]);
  const int seconds = argc > 4 ? std::atoi(argv[4]) : 20;
  World world(config);
  const double length = 1.0 / rods;
  const double drop = std::sqrt(std::max(0.0, 1.0 - span * span));
  std::vector<ParticleId> knots;
  for (int i = 1; i < rods; ++i) {
    ParticleSpec spec;
    spec.position = length * Vec3(i * span, 0, -std::min(i, rods - i) * drop);
    spec.inverse_mass = rods;
    spec.radius = 0.01;
    knots.push_back(*world.addParticle(spec));
  }
  world.addLink(Rod::anchoredAt(knots.front(), Vec3::Zero(), length));
  for (int i = 1; i < rods - 1; ++i) world.addLink(Rod::between(knots[i - 1], knots[i], length));
  world.addLink(Rod::anchoredAt(knots.back(), Vec3(span, 0, 0), length));
  const auto at = [&world](const ParticleId id) {
    return Vec3(world.particles().positions().col(*world.particles().find(id)));
  };
  const double start = world.totalEnergy();
  double most = -1e300;
  for (int s = 1; s <= 60 * seconds; ++s) {
    world.step();
    most = std::max(most, world.totalEnergy() - start);
    if (s % 300 != 0) continue;
    double worst = 0.0;
    for (const Rod& rod : world.links().of<Rod>()) {
      const Vec3 other = rod.anchored() ? rod.anchor : at(rod.b);
      worst = std::max(worst, std::abs((at(rod.a) - other).norm() - length) / length);
    }
    std::printf("span %g t %d: E-E0 %.3e (most %.3e) KE %.3e worst strain %.2e passes %d\n", span,
                s / 60, world.totalEnergy() - start, most, world.kineticEnergy(), worst,
                world.lastContactStats().iterations);
  }
  return 0;
}
