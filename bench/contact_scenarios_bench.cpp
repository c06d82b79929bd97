// Scenarios C (a grid resting on the ground) and D (a settled pile in a box, particle-particle
// collisions) of issue 5, reported per particle-step like integration_bench.cpp: the counter
// particle_step_time is the time of one step divided by the particle count. Both scenes start
// packed at rest and settle for a bounded number of untimed steps, so the set-up stays short at
// 100,000 particles; the counters kinetic_energy_per_particle and contacts show the timed state was
// a settled one.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "mass_aggregate_sim/engine/world.h"
#include "scenario_common.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

using bench::kRadius;
using bench::unitParticle;

constexpr Real kRestitution = 0.2;
constexpr int kSettleSteps = 60;  // one second of simulated time, untimed
constexpr int kMinPileLayers = 10;

Material groundMaterial() { return Material{kRestitution, 0.0}; }

// C: a square grid in the x-z plane, 0.5 m apart (no two particles touch), each sphere resting on
// the ground plane y = 0. Only particle-ground contacts: particle collisions are off.
World groundGridWorld(const std::int64_t n) {
  World world(bench::scenarioConfig());
  world.addPlane(PlaneCollider{Vec3::UnitY(), 0.0, groundMaterial()});
  const auto side = static_cast<std::int64_t>(std::ceil(std::sqrt(static_cast<double>(n))));
  for (std::int64_t i = 0; i < n; ++i) {
    world.addParticle(unitParticle(
        Vec3(0.5 * static_cast<Real>(i % side), kRadius, 0.5 * static_cast<Real>(i / side))));
  }
  return world;
}

// Footprint side of the pile: the widest square at least kMinPileLayers deep that n fills in
// whole layers (1,000: 10 x 10 x 10; 10,000: 25 x 25 x 16; 100,000: 100 x 100 x 10), or a partial
// top layer when there is none.
std::int64_t pileSide(const std::int64_t n) {
  auto side = static_cast<std::int64_t>(
      std::floor(std::sqrt(static_cast<double>(n) / static_cast<double>(kMinPileLayers))));
  side = std::max<std::int64_t>(side, 1);
  for (std::int64_t s = side; s > 1; --s) {
    if (n % (s * s) == 0) return s;
  }
  return side;
}

// D: a cubic lattice of touching spheres in a box of five half-spaces (floor and four walls) that
// touch the outer spheres, particle collisions on. Packed at rest and jammed by the walls, so it
// stays a pile (a cubic stack with room to move buckles) and the settling only absorbs the first
// steps' sag under gravity.
World pileWorld(const std::int64_t n, const Broadphase broadphase) {
  World world(bench::scenarioConfig());
  CollisionSettings settings;
  settings.particle_collisions = true;
  settings.broadphase = broadphase;
  settings.particle_restitution = kRestitution;
  world.setCollisionSettings(settings);
  const Real spacing = 2.0 * kRadius;
  const std::int64_t side = pileSide(n);
  const Real half_width = 0.5 * spacing * static_cast<Real>(side);
  world.addPlane(PlaneCollider{Vec3::UnitY(), 0.0, groundMaterial()});
  world.addPlane(PlaneCollider{Vec3::UnitX(), -half_width, groundMaterial()});
  world.addPlane(PlaneCollider{-Vec3::UnitX(), -half_width, groundMaterial()});
  world.addPlane(PlaneCollider{Vec3::UnitZ(), -half_width, groundMaterial()});
  world.addPlane(PlaneCollider{-Vec3::UnitZ(), -half_width, groundMaterial()});
  const Real first = -0.5 * spacing * static_cast<Real>(side - 1);
  for (std::int64_t i = 0; i < n; ++i) {
    const std::int64_t layer = i / (side * side);
    const std::int64_t in_layer = i % (side * side);
    world.addParticle(unitParticle(Vec3(first + spacing * static_cast<Real>(in_layer % side),
                                        kRadius + spacing * static_cast<Real>(layer),
                                        first + spacing * static_cast<Real>(in_layer / side))));
  }
  return world;
}

void settle(World& world) {
  for (int s = 0; s < kSettleSteps; ++s) world.step();
}

void runContactSteps(benchmark::State& state, World& world) {
  const std::uint64_t divergences_before = world.divergenceCount();
  for (auto _ : state) {
    world.step();
    benchmark::DoNotOptimize(world.particles().positions().data());
    benchmark::ClobberMemory();
  }
  const auto n = static_cast<double>(world.particles().size());
  state.counters["particle_step_time"] = benchmark::Counter(
      n, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["particles"] = n;
  state.counters["contacts"] = static_cast<double>(world.lastContactStats().contacts);
  state.counters["kinetic_energy_per_particle"] = world.kineticEnergy() / n;
  state.counters["velocity_passes"] = world.lastContactStats().velocity_iterations;
  state.counters["position_passes"] = world.lastContactStats().position_iterations;
  state.counters["divergences"] = static_cast<double>(world.divergenceCount() - divergences_before);
}

void BM_ScenarioC_GroundGrid(benchmark::State& state) {
  World world = groundGridWorld(state.range(0));
  settle(world);
  runContactSteps(state, world);
}

void BM_ScenarioD_SettledPile(benchmark::State& state) {
  const auto broadphase = static_cast<Broadphase>(state.range(1));
  state.SetLabel(broadphaseName(broadphase));
  World world = pileWorld(state.range(0), broadphase);
  settle(world);
  runContactSteps(state, world);
}

void pileArguments(benchmark::internal::Benchmark* bench) {
  for (const Broadphase broadphase : {Broadphase::kSortAndSweep, Broadphase::kUniformGrid}) {
    for (const std::int64_t n : {1000, 10000, 100000}) {
      bench->Args({n, static_cast<std::int64_t>(broadphase)});
    }
  }
}

BENCHMARK(BM_ScenarioC_GroundGrid)->Arg(1000)->Arg(10000)->Arg(100000);
BENCHMARK(BM_ScenarioD_SettledPile)->Apply(pileArguments)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
