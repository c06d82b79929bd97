// The dense drop of issue 13 (dense_drop_scene.h): 8,000 spheres falling up to 4 m into a 2 m box
// of half-spaces. BM_DenseDrop_Fall times the whole ten seconds of the drop as one run (the cost
// of a violent scene: impacts, a growing pile, spheres pressed against the walls), and reports
// how it ended: spheres outside the box and kinetic energy. BM_DenseDrop_SettledStep times steps
// of the pile it left, with the at-rest counters of the other contact scenes and the count
// outside.
#include <benchmark/benchmark.h>

#include <chrono>
#include <memory>

#include "dense_drop_scene.h"
#include "mass_aggregate_sim/engine/world/world.h"
#include "scenario_common.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

constexpr int kDropSeconds = 10;
constexpr const char* kSceneName = "dense drop after 10 s";

World droppedWorld() {
  World world = dense_drop::makeWorld();
  for (int s = 0; s < kDropSeconds * dense_drop::kStepsPerSecond; ++s) world.step();
  return world;
}

void BM_DenseDrop_Fall(benchmark::State& state) {
  std::unique_ptr<World> world;
  const int steps = kDropSeconds * dense_drop::kStepsPerSecond;
  double seconds = 0.0;
  for (auto _ : state) {
    state.PauseTiming();
    world = std::make_unique<World>(dense_drop::makeWorld());
    state.ResumeTiming();
    const auto start = std::chrono::steady_clock::now();
    for (int s = 0; s < steps; ++s) world->step();
    seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  const auto n = static_cast<double>(world->particles().size());
  state.counters["particle_step_time"] = benchmark::Counter(
      n * steps, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["particles"] = n;
  state.counters["outside"] = static_cast<double>(dense_drop::spheresOutside(*world));
  state.counters["kinetic_energy"] = world->kineticEnergy();
  state.counters["max_penetration"] = world->lastContactStats().max_penetration;
  bench::keepScene(kSceneName, *world, seconds);
}

void BM_DenseDrop_SettledStep(benchmark::State& state) {
  World world = bench::settledScene(kSceneName, droppedWorld);
  bench::runContactSteps(state, world);
  state.counters["outside"] = static_cast<double>(dense_drop::spheresOutside(world));
}

BENCHMARK(BM_DenseDrop_Fall)->Iterations(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DenseDrop_SettledStep)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
