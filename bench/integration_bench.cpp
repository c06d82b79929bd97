// Scenarios A (free fall) and B (spring chains) of issue 5, reported per particle-step:
// the counter particle_step_time is the wall time of one step divided by the particle count.
// A and B also report floor_ratio: the time over that of their floor loop (bandwidth_floor.h) at
// the same size, measured right after them in the same run.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <utility>

#include "bandwidth_floor.h"
#include "mass_aggregate_sim/engine/world/world.h"
#include "scenario_common.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

using bench::unitParticle;

constexpr int kChainLength = 100;

// Particles on a square grid in the x-z plane, 2 m apart, all falling.
World freeFallWorld(const std::int64_t n) {
  World world(bench::scenarioConfig(Integrator::kSemiImplicitEuler));
  const std::int64_t side = 1000;
  for (std::int64_t i = 0; i < n; ++i) {
    const Vec3 p(2.0 * static_cast<Real>(i % side), 100.0, 2.0 * static_cast<Real>(i / side));
    world.addParticle(unitParticle(p));
  }
  return world;
}

// Chains of 100 particles along x, 1 m apart, neighbours joined by springs (k = 10, rest 1).
// Every other particle starts 0.1 m up so the springs work from the first step.
World springChainWorld(const std::int64_t n, const Integrator integrator) {
  World world(bench::scenarioConfig(integrator));
  const std::int64_t chains = n / kChainLength;
  for (std::int64_t c = 0; c < chains; ++c) {
    ParticleId previous;
    for (int j = 0; j < kChainLength; ++j) {
      const Vec3 p(static_cast<Real>(j), 0.1 * static_cast<Real>(j % 2),
                   2.0 * static_cast<Real>(c));
      const ParticleId id = world.addParticle(unitParticle(p)).value();
      if (j > 0) {
        Spring spring;
        spring.a = previous;
        spring.b = id;
        spring.stiffness = 10.0;
        spring.rest_length = 1.0;
        world.addGenerator(spring);
      }
      previous = id;
    }
  }
  return world;
}

void reportPerParticleStep(benchmark::State& state, const World& world, const double resets) {
  const auto n = static_cast<double>(world.particles().size());
  // Rate of particle-steps per second, inverted: seconds per particle-step.
  state.counters["particle_step_time"] = benchmark::Counter(
      n, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["particles"] = n;
  state.counters["resets"] = resets;
}

// Steps the world; a scene the integrator cannot hold (explicit Euler on springs gains energy
// every step) is restored from its start, untimed, whenever the world reports a divergence, so
// the figure is the cost of stepping finite states. Returns the wall time of the timed loop.
double runSteps(benchmark::State& state, World& world) {
  world.step();  // warm the caches (d^dt, scratch arrays) outside the timed loop
  const World start = world;
  double resets = 0;
  const auto loop_start = std::chrono::steady_clock::now();
  for (auto _ : state) {
    world.step();
    benchmark::DoNotOptimize(world.particles().positions().data());
    benchmark::ClobberMemory();
    if (world.divergenceCount() != 0) {
      state.PauseTiming();
      world = start;
      ++resets;
      state.ResumeTiming();
    }
  }
  const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - loop_start;
  reportPerParticleStep(state, world, resets);
  return elapsed.count();
}

// Seconds per pass of a floor loop (bandwidth_floor.h), over `passes` passes.
template <typename Floor>
double floorSeconds(Floor floor, const std::int64_t passes) {
  floor.step();  // the pages are touched before the clock starts
  const auto start = std::chrono::steady_clock::now();
  for (std::int64_t p = 0; p < passes; ++p) {
    floor.step();
    benchmark::DoNotOptimize(floor.positions());
    benchmark::ClobberMemory();
  }
  const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
  return elapsed.count() / static_cast<double>(passes);
}

// floor_ratio: a scenario's step time over its floor's pass at the same size, from as many floor
// passes as it took steps (at least 100), after its timed loop.
template <typename Floor>
void reportFloorRatio(benchmark::State& state, const double seconds, Floor floor) {
  const std::int64_t steps = std::max<std::int64_t>(state.iterations(), 1);
  const double pass = floorSeconds(std::move(floor), std::max<std::int64_t>(steps, 100));
  state.counters["floor_ratio"] = seconds / static_cast<double>(steps) / pass;
}

// Times a floor loop, reported per particle-step as the scenarios are.
template <typename Floor>
void timeFloor(benchmark::State& state, Floor& floor) {
  for (auto _ : state) {
    floor.step();
    benchmark::DoNotOptimize(floor.positions());
    benchmark::ClobberMemory();
  }
  state.counters["particle_step_time"] = benchmark::Counter(
      static_cast<double>(floor.size()),
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["particles"] = static_cast<double>(floor.size());
}

void BM_ScenarioA_FreeFall(benchmark::State& state) {
  World world = freeFallWorld(state.range(0));
  const double seconds = runSteps(state, world);
  reportFloorRatio(state, seconds, bench::FloorArrays(world.particles().size()));
}

void BM_ScenarioB_SpringChains(benchmark::State& state) {
  World world = springChainWorld(state.range(0), Integrator::kSemiImplicitEuler);
  const double seconds = runSteps(state, world);
  reportFloorRatio(state, seconds, bench::SpringChainFloor(world.particles().size(), kChainLength));
}

// Scenario B without the energy guard (WorldConfig::energy_growth_limit = 0): what the guard costs.
void BM_ScenarioB_SpringChainsNoEnergyGuard(benchmark::State& state) {
  World world = springChainWorld(state.range(0), Integrator::kSemiImplicitEuler);
  WorldConfig config = world.config();
  config.energy_growth_limit = 0.0;
  world.setConfig(config);
  runSteps(state, world);
}

void BM_ScenarioB_Integrator(benchmark::State& state) {
  const auto integrator = static_cast<Integrator>(state.range(1));
  state.SetLabel(integratorName(integrator));
  World world = springChainWorld(state.range(0), integrator);
  runSteps(state, world);
}

void integratorArguments(benchmark::internal::Benchmark* bench) {
  const Integrator all[] = {Integrator::kExplicitEuler,
                            Integrator::kSemiImplicitEuler,
                            Integrator::kPositionVerlet,
                            Integrator::kVelocityVerlet,
                            Integrator::kRk4,
                            Integrator::kImplicitEuler};
  for (const Integrator integrator : all) {
    for (const std::int64_t n : {1000, 10000, 100000}) {
      bench->Args({n, static_cast<std::int64_t>(integrator)});
    }
  }
}

// The floor under scenario A (bandwidth_floor.h): the fastest loop we could write over the bytes
// A's step must move.
void BM_ScenarioA_BandwidthFloor(benchmark::State& state) {
  bench::FloorArrays floor(static_cast<std::size_t>(state.range(0)));
  timeFloor(state, floor);
}

// The floor under scenario B (bandwidth_floor.h): one pass doing the least B's step must do.
void BM_ScenarioB_Floor(benchmark::State& state) {
  bench::SpringChainFloor floor(static_cast<std::size_t>(state.range(0)), kChainLength);
  timeFloor(state, floor);
}

BENCHMARK(BM_ScenarioA_FreeFall)->Arg(1000)->Arg(10000)->Arg(100000)->Arg(1000000);
BENCHMARK(BM_ScenarioA_BandwidthFloor)->Arg(1000)->Arg(10000)->Arg(100000)->Arg(1000000);
BENCHMARK(BM_ScenarioB_SpringChains)->Arg(1000)->Arg(10000)->Arg(100000)->Arg(1000000);
BENCHMARK(BM_ScenarioB_Floor)->Arg(1000)->Arg(10000)->Arg(100000)->Arg(1000000);
BENCHMARK(BM_ScenarioB_SpringChainsNoEnergyGuard)->Arg(1000)->Arg(10000)->Arg(100000);
BENCHMARK(BM_ScenarioB_Integrator)->Apply(integratorArguments);

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
