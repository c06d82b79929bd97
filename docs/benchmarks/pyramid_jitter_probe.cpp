// A pyramid set a little off Box2D's layout (docs/BENCHMARKS.md, 2026-11-28 session 18): the boxes
// of a row `spacing` m apart centre to centre (1: touching), each box moved along x by a uniform
// draw in [-jitter, jitter], and each row lifted `gap` more than the one below. Prints, every
// PERIOD frames (120 unless set), the kinetic energy, how many boxes sleep and how far the top box
// dropped. Build and run from the repository root after scripts/bench.sh has built the engine:
//   g++ -std=c++17 -O2 -I include -I bench/rigid -I /usr/include/eigen3 \
//     docs/benchmarks/pyramid_jitter_probe.cpp bench/rigid/rigid_scenes.cpp \
//     -o /tmp/pyramid_jitter_probe -L ~/mass_aggregate_sim_ws/devel/lib \
//     -lmass_aggregate_sim_engine -Wl,-rpath,$HOME/mass_aggregate_sim_ws/devel/lib
//   /tmp/pyramid_jitter_probe 20 0.002 0 1 600 1.01  # base, jitter, gap, seed, frames, spacing
//   SLEEP=1 PERIOD=15 /tmp/pyramid_jitter_probe 100 0.002 0 1 300
// Switches: SLEEP (sleeping on; off by default), NOGUESS, NOSHOCK, SUB=n, IT=n, and
// GUESSFROM=f / GUESSUNTIL=f (load guesses only from frame f on / before frame f).
#include <cstdio>
#include <cstdlib>

#include "engine_scene.h"
#include "mass_aggregate_sim/engine/world/world.h"
#include "rigid_scenes.h"
using namespace mass_aggregate_sim;
using engine::Vec3;
int main(int argc, char** argv) {
  const int base = argc > 1 ? atoi(argv[1]) : 20;
  const double jitter = argc > 2 ? atof(argv[2]) : 0.002;
  const double gap = argc > 3 ? atof(argv[3]) : 0.0;
  const int seed = argc > 4 ? atoi(argv[4]) : 1;
  const int frames = argc > 5 ? atoi(argv[5]) : 600;
  const double spacing = argc > 6 ? atof(argv[6]) : 1.0;
  const int period = getenv("PERIOD") ? atoi(getenv("PERIOD")) : 120;
  engine::BodySettings settings;
  settings.sleep = getenv("SLEEP") != nullptr;
  if (getenv("NOGUESS")) settings.guess_loads = false;
  if (getenv("NOSHOCK")) settings.shock_propagation = false;
  if (getenv("SUB")) settings.substeps = atoi(getenv("SUB"));
  if (getenv("IT")) settings.iterations = atoi(getenv("IT"));
  const int guess_from = getenv("GUESSFROM") ? atoi(getenv("GUESSFROM")) : 0;
  const int guess_until = getenv("GUESSUNTIL") ? atoi(getenv("GUESSUNTIL")) : 1 << 30;
  auto scene = bench::rigid::pyramid(base);
  bench::rigid::SplitMix64 rng(seed);
  for (auto& body : scene.bodies) {
    const double row = body.position.z() - 0.5;
    body.position.x() = spacing * body.position.x() + rng.uniform(-jitter, jitter);
    body.position.z() += row * gap;
  }
  engine::World world = bench::rigid::engineWorld(scene, settings);
  const auto& bodies = world.bodies();
  const std::size_t top = bodies.size() - 1;
  const Vec3 start = bodies.position(top);
  for (int f = 0; f < frames; ++f) {
    engine::BodySettings now = world.bodySettings();
    now.guess_loads = settings.guess_loads && f >= guess_from && f < guess_until;
    world.setBodySettings(now);
    world.step();
    if ((f + 1) % period != 0) continue;
    int asleep = 0;
    for (std::size_t i = 0; i < bodies.size(); ++i) asleep += bodies.awake(i) ? 0 : 1;
    std::printf("t %.2f KE %.3g asleep %d top_drop %.3g mm\n", (f + 1) / 60.0,
                world.kineticEnergy(), asleep, 1000 * (start.z() - bodies.position(top).z()));
  }
}
