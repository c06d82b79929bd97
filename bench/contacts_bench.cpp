// Per-step cost of a settled pile of particles in a box, with particle-particle collisions.
// Args: particle count, broadphase (0 sort_and_sweep, 1 uniform_grid).
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <string>

#include "mass_aggregate_sim/engine/world/world.h"
#include "scenario_common.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

constexpr Real kPileRadius = 0.025;
constexpr int kDropLayers = 10;

// The pile of test/engine/pile_test.cpp, scaled: particles of radius 2.5 cm dropped from a loose
// lattice, ten deep, 9 cm apart across, into a square box, where they settle about two and a half
// particles deep. Four seconds of settling come before anything is timed.
World settledPile(const int count, const Broadphase broadphase) {
  WorldConfig config;
  config.gravity = Vec3(0.0, 0.0, -9.81);
  World world(config);
  CollisionSettings settings;
  settings.particle_collisions = true;
  settings.broadphase = broadphase;
  settings.particle_restitution = 0.2;
  settings.particle_friction = 0.3;
  world.setCollisionSettings(settings);
  const int side = static_cast<int>(std::ceil(std::sqrt(static_cast<Real>(count) / kDropLayers)));
  const Real spacing = 0.09;
  const Real half_width = 0.5 * side * spacing + 0.05;
  const Material material{0.2, 0.3};
  world.addCollider(PlaneCollider{Vec3::UnitZ(), 0.0, material});
  world.addCollider(PlaneCollider{Vec3::UnitX(), -half_width, material});
  world.addCollider(PlaneCollider{-Vec3::UnitX(), -half_width, material});
  world.addCollider(PlaneCollider{Vec3::UnitY(), -half_width, material});
  world.addCollider(PlaneCollider{-Vec3::UnitY(), -half_width, material});
  std::mt19937 rng(11);
  std::uniform_real_distribution<Real> jitter(-0.005, 0.005);
  for (int n = 0; n < count; ++n) {
    const int i = n % side;
    const int j = (n / side) % side;
    const int k = n / (side * side);
    ParticleSpec spec;
    spec.position = Vec3(-0.5 * side * spacing + (i + 0.5) * spacing + jitter(rng),
                         -0.5 * side * spacing + (j + 0.5) * spacing + jitter(rng),
                         0.1 + 0.06 * k + jitter(rng));
    spec.radius = kPileRadius;
    spec.inverse_mass = 10.0;
    world.addParticle(spec);
  }
  for (int s = 0; s < 240; ++s) world.step();
  return world;
}

void BM_ContactsSettledPileStep(benchmark::State& state) {
  const int count = static_cast<int>(state.range(0));
  const Broadphase broadphase =
      state.range(1) == 0 ? Broadphase::kSortAndSweep : Broadphase::kUniformGrid;
  // Settled once per run, not once per trial (scenario_common.h).
  World world = bench::settledScene(
      "settled pile/" + std::to_string(count) + "/" + std::to_string(state.range(1)),
      [&] { return settledPile(count, broadphase); });
  for (auto _ : state) world.step();
  const ContactStats& stats = world.lastContactStats();
  state.SetLabel(broadphaseName(broadphase));
  state.counters["contacts"] = static_cast<double>(stats.contacts);
  state.counters["vel_iters"] = stats.velocity_iterations;
  state.counters["pos_iters"] = stats.position_iterations;
  state.counters["max_pen_mm"] = 1000.0 * stats.max_penetration;
  state.counters["kinetic_J"] = world.kineticEnergy();
  state.counters["per_particle_step"] = benchmark::Counter(
      static_cast<double>(count) * static_cast<double>(state.iterations()),
      benchmark::Counter::kIsRate | benchmark::Counter::kInvert, benchmark::Counter::kIs1000);
}
BENCHMARK(BM_ContactsSettledPileStep)
    ->ArgNames({"particles", "grid"})
    ->Args({1000, 0})
    ->Args({1000, 1})
    ->Args({10000, 0})
    ->Args({10000, 1})
    ->Args({100000, 0})
    ->Args({100000, 1})
    ->Unit(benchmark::kMillisecond)
    ->MinTime(1.0);

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
