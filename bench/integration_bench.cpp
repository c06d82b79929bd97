// Scenarios A (free fall) and B (spring chains) of issue 5, reported per particle-step:
// the counter particle_step_time is the wall time of one step divided by the particle count.
#include <benchmark/benchmark.h>

#include <cstdint>
#include <vector>

#include "mass_aggregate_sim/engine/world.h"
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
        world.addSpring(spring);
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
// the figure is the cost of stepping finite states.
void runSteps(benchmark::State& state, World& world) {
  world.step();  // warm the caches (d^dt, scratch arrays) outside the timed loop
  const World start = world;
  double resets = 0;
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
  reportPerParticleStep(state, world, resets);
}

void BM_ScenarioA_FreeFall(benchmark::State& state) {
  World world = freeFallWorld(state.range(0));
  runSteps(state, world);
}

void BM_ScenarioB_SpringChains(benchmark::State& state) {
  World world = springChainWorld(state.range(0), Integrator::kSemiImplicitEuler);
  runSteps(state, world);
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

// The floor under scenario A: a loop that streams the bytes A's integration pass moves per
// particle (reads own acceleration, mobility, damping, velocity and position: 11 doubles; writes
// acceleration, velocity and position: 9) with one addition per value, so the ratio of A to it
// says how close A is to what the memory system delivers at that size.
void BM_ScenarioA_BandwidthFloor(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  std::vector<Real> own(3 * n, 0.0), v(3 * n, 1.0), x(3 * n, 2.0), a(3 * n, 0.0);
  std::vector<Real> mobility(n, 1.0), damping(n, 0.99);
  for (auto _ : state) {
    for (std::size_t i = 0; i < n; ++i) {
      const Real scale = mobility[i] + damping[i];
      for (std::size_t c = 0; c < 3; ++c) {
        const std::size_t k = 3 * i + c;
        a[k] = own[k] + scale;
        v[k] = v[k] + scale;
        x[k] = x[k] + scale;
      }
    }
    benchmark::DoNotOptimize(x.data());
    benchmark::ClobberMemory();
  }
  state.counters["particle_step_time"] =
      benchmark::Counter(static_cast<double>(n), benchmark::Counter::kIsIterationInvariantRate |
                                                     benchmark::Counter::kInvert);
  state.counters["particles"] = static_cast<double>(n);
}

BENCHMARK(BM_ScenarioA_FreeFall)->Arg(1000)->Arg(10000)->Arg(100000)->Arg(1000000);
BENCHMARK(BM_ScenarioA_BandwidthFloor)->Arg(1000)->Arg(10000)->Arg(100000)->Arg(1000000);
BENCHMARK(BM_ScenarioB_SpringChains)->Arg(1000)->Arg(10000)->Arg(100000)->Arg(1000000);
BENCHMARK(BM_ScenarioB_SpringChainsNoEnergyGuard)->Arg(1000)->Arg(10000)->Arg(100000);
BENCHMARK(BM_ScenarioB_Integrator)->Apply(integratorArguments);

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
