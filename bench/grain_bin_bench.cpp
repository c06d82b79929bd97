// Grains poured into a bin (grain_bin_scene.h), the particles-on-bodies scene a user pours:
// BM_GrainBin/N/0 with the bin a dynamic body, /N/1 with the same bin as five static colliders
// (the particles' own pile: the floor the body bin is measured against). Each settles 4 s untimed
// (setup_seconds), then times frames of the settled pile, reporting beside the time the at-rest
// counters of the other contact scenes, the grains outside the bin, how far the bin's centre of
// mass is from where it rests (bin_offset_m; 0 with the colliders) and the deepest grain-bin
// overlap (grain_bin_overlap_m; the colliders' overlaps are in max_penetration).
#include <benchmark/benchmark.h>

#include <string>

#include "grain_bin_scene.h"
#include "scenario_common.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

constexpr int kSettleSeconds = 4;

void BM_GrainBin(benchmark::State& state) {
  const auto grains = static_cast<int>(state.range(0));
  const bool as_colliders = state.range(1) != 0;
  const std::string name =
      "grain bin/" + std::to_string(grains) + (as_colliders ? "/colliders" : "/body");
  grain_bin::Scene made = grain_bin::makeScene(grains, as_colliders);
  const BodyId bin = made.bin;
  const Real bin_z = made.bin_z;
  World world = bench::settledScene(name, [&made] {
    for (int s = 0; s < kSettleSeconds * grain_bin::kStepsPerSecond; ++s) made.world.step();
    return made.world;
  });
  bench::runContactSteps(state, world);
  state.counters["outside"] = grain_bin::grainsOutside(world);
  state.counters["grain_bin_overlap_m"] = grain_bin::deepestGrainInBin(world);
  state.counters["bin_offset_m"] =
      as_colliders ? 0.0 : world.bodies().position(*world.bodies().find(bin)).z() - bin_z;
  state.SetLabel(name);
}

BENCHMARK(BM_GrainBin)
    ->Args({1000, 0})
    ->Args({1000, 1})
    ->Args({4000, 0})
    ->Args({4000, 1})
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
