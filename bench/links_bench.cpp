// Links as users swing them: a rope of rods (or cables) from an anchor, released from the
// horizontal and timed over its first 5 s of whipping at the defaults (60 Hz, 1 substep), with
// what it kept beside the time: the fraction of its energy lost (above hanging straight down)
// and the worst stretch of a segment; and a rope tied between two anchors.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "mass_aggregate_sim/engine/world/world.h"
#include "rope_scene.h"
#include "scenario_common.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

constexpr int kRopeSteps = 300;

struct Rope {
  World world;
  std::vector<ParticleId> knots;
};

// Released from the horizontal (along +x) or hanging straight down (along -y).
Rope ropeWorld(const std::int64_t n, const bool cables, const int substeps,
               const bool hanging = false) {
  WorldConfig config = bench::scenarioConfig();
  config.substeps = substeps;
  Rope rope{World(config), {}};
  const int knots = static_cast<int>(n);
  rope.knots = rope::add(rope.world, knots, cables, 0.25 * rope::segment(knots),
                         hanging ? Vec3(0.0, -1.0, 0.0) : Vec3(1.0, 0.0, 0.0));
  return rope;
}

// Kinetic plus potential energy, gravity along -y.
Real ropeEnergy(const World& world) {
  const auto& x = world.particles().positions();
  const auto& v = world.particles().velocities();
  Real energy = 0.0;
  for (Eigen::Index i = 0; i < x.cols(); ++i) {
    const Real mass = 1.0 / world.particles().inverseMasses()[i];
    energy += mass * (0.5 * v.col(i).squaredNorm() + 9.81 * x(1, i));
  }
  return energy;
}

Real worstStretch(const Rope& rope, const Real segment) {
  const auto& x = rope.world.particles().positions();
  Real worst = std::abs(x.col(0).norm() - segment);
  for (Eigen::Index i = 1; i < x.cols(); ++i) {
    worst = std::max(worst, (x.col(i) - x.col(i - 1)).norm() - segment);
  }
  return worst / segment;
}

// Args: knots, cables (0 rods, 1 cables), substeps.
void BM_LinksSwingingRope(benchmark::State& state) {
  const std::int64_t n = state.range(0);
  const bool cables = state.range(1) != 0;
  const auto substeps = static_cast<int>(state.range(2));
  const Real segment = rope::segment(static_cast<int>(n));
  // Hanging straight down, its centre of mass is half its length below the anchor.
  const Real hanging =
      -9.81 * rope::kMass * 0.5 * rope::kLength * (1.0 + 1.0 / static_cast<Real>(n));
  for (auto _ : state) {
    state.PauseTiming();
    Rope rope = ropeWorld(n, cables, substeps);
    state.ResumeTiming();
    for (int s = 0; s < kRopeSteps; ++s) rope.world.step();
  }
  // The same run again, untimed (it is deterministic), for what the rope kept.
  Rope rope = ropeWorld(n, cables, substeps);
  const Real start = ropeEnergy(rope.world);
  Real worst = 0.0;
  Real passes = 0.0;
  for (int s = 0; s < kRopeSteps; ++s) {
    rope.world.step();
    worst = std::max(worst, worstStretch(rope, segment));
    passes += rope.world.lastContactStats().iterations;
  }
  const Real lost = (start - ropeEnergy(rope.world)) / (start - hanging);
  // Seconds a step.
  state.counters["step_time"] = benchmark::Counter(
      kRopeSteps, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["energy_lost"] = lost;
  state.counters["worst_stretch"] = worst;
  // Velocity and position passes a step (of the last substep), on average.
  state.counters["passes"] = passes / kRopeSteps;
}

// The same rope hanging still: what a link row costs when nothing turns. Args: knots, substeps.
void BM_LinksHangingRope(benchmark::State& state) {
  const std::int64_t n = state.range(0);
  const auto substeps = static_cast<int>(state.range(1));
  Rope rope = ropeWorld(n, false, substeps, true);
  for (auto _ : state) rope.world.step();
  state.counters["kinetic_energy"] = rope.world.kineticEnergy();
  state.counters["passes"] = rope.world.lastContactStats().iterations;
  state.counters["worst_stretch"] = worstStretch(rope, rope::segment(static_cast<int>(n)));
}

// A rope of 20 rods tied between two anchors, released as a V of its lengths (rope::tie), timed
// over 5 s with what it kept: the most its energy rose above the start (J; negative when it
// never did) and the worst strain of a rod at the end. Args: span (cm), substeps.
void BM_LinksTiedRope(benchmark::State& state) {
  constexpr int kRods = 20;
  const Real span = static_cast<Real>(state.range(0)) / 100.0;
  const auto substeps = static_cast<int>(state.range(1));
  const auto tied = [&] {
    WorldConfig config = bench::scenarioConfig();
    config.substeps = substeps;
    World world(config);
    rope::tie(world, kRods, span, -Vec3::UnitY(), 0.25 * rope::segment(kRods));
    return world;
  };
  for (auto _ : state) {
    state.PauseTiming();
    World world = tied();
    state.ResumeTiming();
    for (int s = 0; s < kRopeSteps; ++s) world.step();
  }
  World world = tied();
  const Real start = ropeEnergy(world);
  Real most = -std::numeric_limits<Real>::infinity();
  Real passes = 0.0;
  for (int s = 0; s < kRopeSteps; ++s) {
    world.step();
    most = std::max(most, ropeEnergy(world) - start);
    passes += world.lastContactStats().iterations;
  }
  const auto& x = world.particles().positions();
  const Real length = rope::segment(kRods);
  Real worst = std::abs(x.col(0).norm() - length);
  for (Eigen::Index i = 1; i < x.cols(); ++i) {
    worst = std::max(worst, std::abs((x.col(i) - x.col(i - 1)).norm() - length));
  }
  worst = std::max(worst, std::abs((x.col(x.cols() - 1) - span * Vec3::UnitX()).norm() - length));
  state.counters["step_time"] = benchmark::Counter(
      kRopeSteps, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["most_gained"] = most;
  state.counters["worst_stretch"] = worst / length;
  state.counters["passes"] = passes / kRopeSteps;
}

BENCHMARK(BM_LinksHangingRope)->Args({20, 1})->Args({200, 4})->Unit(benchmark::kMicrosecond);

BENCHMARK(BM_LinksSwingingRope)
    ->Args({20, 0, 1})
    ->Args({20, 1, 1})
    ->Args({20, 0, 4})
    ->Args({200, 0, 4})
    ->Unit(benchmark::kMillisecond);

BENCHMARK(BM_LinksTiedRope)
    ->Args({99, 1})
    ->Args({50, 1})
    ->Args({99, 4})
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
