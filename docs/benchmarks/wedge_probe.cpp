// The random drop's wedged light box, frame by frame (docs/BENCHMARKS.md, 2026-11-27, session 16).
// Build and run from the repository root after scripts/bench.sh has built the engine:
//   g++ -std=c++17 -O2 -I include -I bench/rigid -I /usr/include/eigen3 \
//     docs/benchmarks/wedge_probe.cpp bench/rigid/rigid_scenes.cpp \
//     -o /tmp/wedge_probe -L ~/mass_aggregate_sim_ws/devel/lib -lmass_aggregate_sim_engine \
//     -Wl,-rpath,$HOME/mass_aggregate_sim_ws/devel/lib
//   SEED=1 AT=420 FRAMES=12 /tmp/wedge_probe
// Steps the 1,000-box drop (4 x 2, sleeping off) AT frames, takes the deepest body pair and its
// lighter box, then for FRAMES more frames prints that box's position, velocity and angular
// velocity and, for each of its contacts, the other box's mass (0: the ground), the normal, the
// points, the least separation and the summed normal impulse. From frame AT on these settings may
// change: SUB=n substeps, ITERS=n iterations, RELAXS=n relaxing passes, PUSH=x max_push_speed,
// HERTZ=x contact_hertz, DAMP=x contact_damping_ratio, SPEC=x speculative_distance, NOGUESS=1
// no load guesses, NOSHOCK=1 no shock pass.
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>

#include "engine_scene.h"
#include "mass_aggregate_sim/engine/world/world.h"
using namespace mass_aggregate_sim;
using engine::Vec3;

namespace {

bool has(const char* name) { return std::getenv(name) != nullptr; }
double number(const char* name, const double otherwise) {
  return has(name) ? std::atof(std::getenv(name)) : otherwise;
}

}  // namespace

int main() {
  const auto scene = bench::rigid::randomDrop(1000, static_cast<std::uint64_t>(number("SEED", 1)));
  engine::BodySettings settings;
  settings.sleep = false;
  engine::World world = bench::rigid::engineWorld(scene, settings);
  const int at = static_cast<int>(number("AT", 420));
  for (int f = 0; f < at; ++f) world.step();
  engine::BodySettings later = world.bodySettings();
  later.substeps = static_cast<int>(number("SUB", later.substeps));
  later.iterations = static_cast<int>(number("ITERS", later.iterations));
  later.relax_iterations = static_cast<int>(number("RELAXS", later.relax_iterations));
  later.max_push_speed = number("PUSH", later.max_push_speed);
  later.contact_hertz = number("HERTZ", later.contact_hertz);
  later.contact_damping_ratio = number("DAMP", later.contact_damping_ratio);
  later.speculative_distance = number("SPEC", later.speculative_distance);
  if (has("NOGUESS")) later.guess_loads = false;
  if (has("NOSHOCK")) later.shock_propagation = false;
  world.setBodySettings(later);

  const auto& bodies = world.bodies();
  double deepest = 0.0;
  engine::BodyContactReport pair;
  for (const auto& c : world.bodyContacts()) {
    if (c.other != engine::BodyContactReport::Other::kBody) continue;
    for (const auto& p : c.points) {
      if (-p.separation > deepest) {
        deepest = -p.separation;
        pair = c;
      }
    }
  }
  if (deepest == 0.0) {
    std::printf("no overlapping pair of boxes at frame %d\n", at);
    return 0;
  }
  const bool a_lighter =
      bodies.mass(*bodies.find(pair.body)) < bodies.mass(*bodies.find(pair.other_body));
  const engine::BodyId light = a_lighter ? pair.body : pair.other_body;
  const int frames = static_cast<int>(number("FRAMES", 30));
  for (int f = 0; f < frames; ++f) {
    world.step();
    const std::size_t i = *bodies.find(light);
    const Vec3 x = bodies.pose(i).position;
    const Vec3 v = bodies.linearVelocity(i);
    const Vec3 w = bodies.angularVelocity(i);
    std::printf("frame %d: x (%.4f %.4f %.4f) v (%.3f %.3f %.3f) w (%.2f %.2f %.2f)\n", at + f + 1,
                x.x(), x.y(), x.z(), v.x(), v.y(), v.z(), w.x(), w.y(), w.z());
    for (const auto& c : world.bodyContacts()) {
      const bool body_pair = c.other == engine::BodyContactReport::Other::kBody;
      if (c.body != light && !(body_pair && c.other_body == light)) continue;
      const double other =
          body_pair ? bodies.mass(*bodies.find(c.body == light ? c.other_body : c.body)) : 0.0;
      double least = 1.0;
      double impulse = 0.0;
      for (const auto& p : c.points) {
        least = std::min(least, p.separation);
        impulse += p.normal_impulse;
      }
      std::printf(
          "  other %.3f kg, n (%.2f %.2f %.2f), %zu points, least separation %.4f m, "
          "normal impulse %.2e N s\n",
          other, c.normal.x(), c.normal.y(), c.normal.z(), c.points.size(), least, impulse);
    }
  }
}
