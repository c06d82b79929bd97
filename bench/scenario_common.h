#pragma once
// The common set-up of issue 5's benchmark scenarios: dt = 1/60 s, mass 1 kg, damping 0.99,
// gravity (0, -9.81, 0), particle radius 0.1 m; and what every contact scene reports.

#include <benchmark/benchmark.h>

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "mass_aggregate_sim/engine/world/world.h"

namespace mass_aggregate_sim {
namespace engine {
namespace bench {

constexpr Real kDt = 1.0 / 60.0;
constexpr Real kDamping = 0.99;
constexpr Real kRadius = 0.1;

inline WorldConfig scenarioConfig(const Integrator integrator = Integrator::kSemiImplicitEuler) {
  WorldConfig config;
  config.dt = kDt;
  config.integrator = integrator;
  config.gravity = Vec3(0.0, -9.81, 0.0);
  return config;
}

inline ParticleSpec unitParticle(const Vec3& position) {
  ParticleSpec spec;
  spec.position = position;
  spec.inverse_mass = 1.0;
  spec.damping = kDamping;
  spec.radius = kRadius;
  return spec;
}

// The settled world of the last scene asked for, by name: Google Benchmark calls a benchmark
// function once per trial (it raises the iteration count until the run is long enough), and each
// trial then copies the world instead of settling it again. A copy steps on exactly as the
// original would (World's copy keeps the contact phase's warm starts and candidate pairs). One
// scene is kept at a time, so a suite run holds one large world, not all of them.
struct SceneCache {
  std::string name;
  std::unique_ptr<World> world;
  double setup_seconds = 0.0;  // wall time it took to make (build and settle)
};

inline SceneCache& sceneCache() {
  static SceneCache cache;
  return cache;
}

// Keeps `world` as the scene `name` (a benchmark that made it on the way, for the next one).
inline void keepScene(const std::string& name, const World& world, const double setup_seconds) {
  SceneCache& cache = sceneCache();
  cache.world.reset();
  cache.world = std::make_unique<World>(world);
  cache.name = name;
  cache.setup_seconds = setup_seconds;
}

inline World settledScene(const std::string& name, const std::function<World()>& make) {
  SceneCache& cache = sceneCache();
  if (!cache.world || cache.name != name) {
    cache.world.reset();
    const auto start = std::chrono::steady_clock::now();
    World world = make();
    const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
    keepScene(name, world, elapsed.count());
  }
  return *cache.world;
}

// The same world on the general contact path: a contact limit no scene reaches turns off the
// collider-only path (contacts made and solved part by part, collider groups in vector lanes),
// so a benchmark can show what that path is worth on a scene (issue 13: a special path stays
// only where it pays 1.3x on a realistic scene).
inline void useGeneralContactPath(World& world) {
  CollisionSettings settings = world.collisionSettings();
  settings.max_contacts = std::size_t{1} << 40;
  world.setCollisionSettings(settings);
}

// Times world.step() of the scene settledScene() gave, and reports per particle-step, with the
// at-rest quality of the state the timed steps ended in: its kinetic energy, the largest overlap
// the contact phase left (m), the contacts and the resolver's passes in the last substep,
// divergences during the timed steps, and the wall time the scene took to build and settle.
// after_step runs after each step (timed with it: keep it to reading a counter).
inline void runContactSteps(benchmark::State& state, World& world,
                            const std::function<void()>& after_step = {}) {
  const std::uint64_t divergences_before = world.divergenceCount();
  for (auto _ : state) {
    world.step();
    if (after_step) after_step();
    benchmark::DoNotOptimize(world.particles().positions().data());
    benchmark::ClobberMemory();
  }
  const auto n = static_cast<double>(world.particles().size());
  const ContactStats& stats = world.lastContactStats();
  state.counters["particle_step_time"] = benchmark::Counter(
      n, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["particles"] = n;
  state.counters["contacts"] = static_cast<double>(stats.contacts);
  state.counters["kinetic_energy_per_particle"] = world.kineticEnergy() / n;
  state.counters["max_penetration"] = stats.max_penetration;
  state.counters["velocity_passes"] = stats.velocity_iterations;
  state.counters["position_passes"] = stats.position_iterations;
  state.counters["divergences"] = static_cast<double>(world.divergenceCount() - divergences_before);
  state.counters["setup_seconds"] = sceneCache().setup_seconds;
}

}  // namespace bench
}  // namespace engine
}  // namespace mass_aggregate_sim
