// Scenarios C (a grid resting on the ground) and D (a settled pile in a box, particle-particle
// collisions) of issue 5, reported per particle-step like integration_bench.cpp: the counter
// particle_step_time is the time of one step divided by the particle count. Both scenes start
// packed at rest and settle for a bounded number of untimed steps, so the set-up stays short at
// 100,000 particles; the counters kinetic_energy_per_particle, max_penetration and contacts show
// the timed state was a settled one. D comes twice: frictionless with r = 0.1 m (issue 5's scene)
// and with friction 0.3 and r = 2.5 cm (issue 13: the scene the frictionless fast paths do not
// serve).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include "mass_aggregate_sim/engine/world/world.h"
#include "scenario_common.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

using bench::kRadius;
using bench::runContactSteps;
using bench::settledScene;
using bench::unitParticle;

constexpr Real kRestitution = 0.2;
constexpr int kSettleSteps = 60;  // one second of simulated time, untimed
constexpr int kMinPileLayers = 10;

Material groundMaterial() { return Material{kRestitution, 0.0}; }

// C: a square grid in the x-z plane, 0.5 m apart (no two particles touch), each sphere resting on
// the ground plane y = 0. Only particle-ground contacts: particle collisions are off.
World groundGridWorld(const std::int64_t n) {
  World world(bench::scenarioConfig());
  world.addCollider(PlaneCollider{Vec3::UnitY(), 0.0, groundMaterial()});
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

// The material of a D pile: the particles' radius, and restitution and friction of particle
// pairs and of the five planes alike.
struct PileMaterial {
  Real radius = kRadius;
  Real restitution = kRestitution;
  Real friction = 0.0;
};

// D: a cubic lattice of touching spheres in a box of five half-spaces (floor and four walls) that
// touch the outer spheres, particle collisions on. Packed at rest and jammed by the walls, so it
// stays a pile (a cubic stack with room to move buckles) and the settling only absorbs the first
// steps' sag under gravity.
World pileWorld(const std::int64_t n, const Broadphase broadphase, const PileMaterial& material) {
  World world(bench::scenarioConfig());
  CollisionSettings settings;
  settings.particle_collisions = true;
  settings.broadphase = broadphase;
  settings.particle_restitution = material.restitution;
  settings.particle_friction = material.friction;
  world.setCollisionSettings(settings);
  const Material walls{material.restitution, material.friction};
  const Real spacing = 2.0 * material.radius;
  const std::int64_t side = pileSide(n);
  const Real half_width = 0.5 * spacing * static_cast<Real>(side);
  world.addCollider(PlaneCollider{Vec3::UnitY(), 0.0, walls});
  world.addCollider(PlaneCollider{Vec3::UnitX(), -half_width, walls});
  world.addCollider(PlaneCollider{-Vec3::UnitX(), -half_width, walls});
  world.addCollider(PlaneCollider{Vec3::UnitZ(), -half_width, walls});
  world.addCollider(PlaneCollider{-Vec3::UnitZ(), -half_width, walls});
  const Real first = -0.5 * spacing * static_cast<Real>(side - 1);
  for (std::int64_t i = 0; i < n; ++i) {
    const std::int64_t layer = i / (side * side);
    const std::int64_t in_layer = i % (side * side);
    ParticleSpec spec = unitParticle(Vec3(first + spacing * static_cast<Real>(in_layer % side),
                                          material.radius + spacing * static_cast<Real>(layer),
                                          first + spacing * static_cast<Real>(in_layer / side)));
    spec.radius = material.radius;
    world.addParticle(spec);
  }
  return world;
}

World settled(World world) {
  for (int s = 0; s < kSettleSteps; ++s) world.step();
  return world;
}

std::string sceneName(const char* scene, const benchmark::State& state) {
  return std::string(scene) + "/" + std::to_string(state.range(0)) + "/" +
         std::to_string(state.range(1));
}

void BM_ScenarioC_GroundGrid(benchmark::State& state) {
  World world = settledScene("C/" + std::to_string(state.range(0)),
                             [&] { return settled(groundGridWorld(state.range(0))); });
  runContactSteps(state, world);
}

void BM_ScenarioC_GroundGrid_GeneralPath(benchmark::State& state) {
  World world = settledScene("C/" + std::to_string(state.range(0)),
                             [&] { return settled(groundGridWorld(state.range(0))); });
  bench::useGeneralContactPath(world);
  runContactSteps(state, world);
}

void BM_ScenarioD_SettledPile(benchmark::State& state) {
  const auto broadphase = static_cast<Broadphase>(state.range(1));
  state.SetLabel(broadphaseName(broadphase));
  World world = settledScene(sceneName("D", state), [&] {
    return settled(pileWorld(state.range(0), broadphase, PileMaterial{}));
  });
  runContactSteps(state, world);
}

// D with particle, floor and wall friction 0.3, restitution 0.2 and particles of r = 2.5 cm.
void BM_ScenarioD_FrictionPile(benchmark::State& state) {
  const auto broadphase = static_cast<Broadphase>(state.range(1));
  state.SetLabel(broadphaseName(broadphase));
  World world = settledScene(sceneName("D friction", state), [&] {
    return settled(pileWorld(state.range(0), broadphase, PileMaterial{0.025, kRestitution, 0.3}));
  });
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
BENCHMARK(BM_ScenarioC_GroundGrid_GeneralPath)->Arg(1000)->Arg(10000)->Arg(100000);
BENCHMARK(BM_ScenarioD_SettledPile)->Apply(pileArguments)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ScenarioD_FrictionPile)->Apply(pileArguments)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
