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
// Arguments: RODS SPAN SUBSTEPS [SECONDS]; with BALL_DROP=z a 1 kg ball of 10 cm radius falls
// from height z onto the middle of the rope (particle collisions on, ground at -0.8 m).
// The last line of each run (20 rods, 1 substep) on 2026-11-30, by engine: energy at 20 s against
// the start (the most it rose above it), and the worst strain then.
//   span   257545a (row by row)   2c6dfa8 (chains, Newton)   a96f853 (held: rows)   d (held: SHAKE)
//   1.0    -                      -                          -0.82 (-0.013), 4.7 %  -0.84
//   (-0.011), 4.7 % 0.999  -0.75 (-0.013), 13 %   +1.7 (+3.1), 2.8 %         -0.72 (-0.013), 4.9 %
//   -0.014 (-0.006), 1e-10 0.99   -0.59 (-0.013), 16 %   +1.4 (+1.5), 5e-14         -0.54
//   (-0.013), 4.5 %  -0.050 (-0.010), 7e-10 0.95   -0.39 (-0.012), 10 %   +0.21 (+0.21), 2e-15
//   -0.35 (-0.013), 3.5 %  -0.11 (-0.010), 9e-14 0.8    -0.26 (-0.011), 7.3 %  -0.05 (+0.07), 2e-13
//   -0.24 (-0.012), 2.2 %  -0.16 (-0.007), 2e-15 0.5    -0.16 (-0.010), 5.8 %  +0.09 (+0.13), 2e-10
//   -0.14 (-0.012), 1.8 %  -0.11 (-0.003), 3e-12
// (d: this commit.) Kinetic energy at 20 s: row by row 1.5e-4 to 2.0e-2 J, chains 8.2e-3 to 2.1 J,
// held rows 3.2e-4 to 9.1e-3 J, held SHAKE 7.6e-4 to 2.7e-3 J (the swing an inextensible rope
// keeps). With BALL_DROP=0.1 at span 0.9 (60 s): held rows 7 % strain under the ball, energy flat
// at -2.8 J; held SHAKE 2e-15 strain, flat at -1.88 J (+0.02 J from 3 s to 55 s), KE 0.02 to
// 0.06 J in both.
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
  const char* ball_drop = std::getenv("BALL_DROP");
  if (ball_drop) {
    CollisionSettings collisions = world.collisionSettings();
    collisions.particle_collisions = true;
    world.setCollisionSettings(collisions);
    PlaneCollider ground;
    ground.offset = -0.8;
    world.addCollider(ground);
  }
  const double length = 1.0 / rods;
  const double drop = std::sqrt(std::max(0.0, 1.0 - span * span));
  std::vector<ParticleId> knots;
  for (int i = 1; i < rods; ++i) {
    ParticleSpec spec;
    spec.position = length * Vec3(i * span, 0, -std::min(i, rods - i) * drop);
    spec.inverse_mass = rods;
    spec.radius = ball_drop ? 0.025 : 0.01;  // knots the ball cannot pass between
    knots.push_back(*world.addParticle(spec));
  }
  world.addLink(Rod::anchoredAt(knots.front(), Vec3::Zero(), length));
  for (int i = 1; i < rods - 1; ++i) world.addLink(Rod::between(knots[i - 1], knots[i], length));
  world.addLink(Rod::anchoredAt(knots.back(), Vec3(span, 0, 0), length));
  if (ball_drop) {
    ParticleSpec ball;
    ball.position = Vec3(0.5 * span + 0.013, 0, std::atof(ball_drop));
    ball.radius = 0.1;
    world.addParticle(ball);
  }
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
