// The engine's rigid bodies on the shared rigid scenes of rigid_scenes.h, measured as
// bullet_peer_bench.cpp measures Bullet, so the two tables compare line for line.
//
// Arguments of every case: /<scene size>/<substeps>/<sleeping>/<iterations>. A frame is one
// World::step() of 1/60 s with BodySettings::substeps and ::iterations as given and every other
// body setting at its default; sleeping = 0 turns sleeping off, 1 keeps the default (an island
// slow for 0.5 s sleeps). The default settings are 4 substeps of 2 iterations; the tall pyramid
// also runs at 8 and 12 substeps of 1 iteration (docs/ACCURACY.md recommends them for piles),
// the random drop at 4 substeps of 3 and 4 iterations, and every scene, sleeping off, at the
// cheaper 1 x 1, 2 x 1 and 2 x 2 (the 210 pyramid, laid exactly and dropped, also at 8 x 1).
//
// Each case builds its scene and simulates 10 s untimed, recording the mean cost of a frame over
// those 10 s (settle_ms: the falling, stacking and settling a user watches), the worst and mean
// deepest overlap over their last 3 s (late_max_pen_m, late_mean_pen_m), how many bodies moved
// more than 1 mm and 1 cm over those 3 s (late_moved_mm, late_moved_cm), how many were in free fall
// over the last frame (in_flight), the kinetic energy of the others inside the walls
// (pile_kinetic_J) and the at-rest quality at their end (counters, rigid_report.h); then it times
// a fixed number of further frames: Time and CPU are per frame, one thread.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "engine_scene.h"
#include "mass_aggregate_sim/engine/world/world.h"
#include "rigid_report.h"
#include "rigid_scenes.h"

namespace mass_aggregate_sim {
namespace bench {
namespace rigid {
namespace {

using engine::BodyId;
using engine::Real;
using engine::Vec3;

class EngineWorld {
 public:
  EngineWorld(const RigidScene& scene, const int substeps, const int iterations,
              const bool sleeping)
      : scene_(scene) {
    engine::BodySettings settings;
    settings.substeps = substeps;
    settings.iterations = iterations;
    settings.sleep = sleeping;
    ids_.reserve(scene.bodies.size());
    world_ = engineWorld(scene, settings, &ids_);
  }

  void stepFrame() { world_.step(); }

  AtRest atRest() const {
    AtRest result;
    const engine::BodyStore& bodies = world_.bodies();
    for (std::size_t k = 0; k < ids_.size(); ++k) {
      if (scene_.bodies[k].isFixed()) continue;
      result.kinetic_energy += kineticEnergy(k);
      const std::size_t i = *bodies.find(ids_[k]);
      if (hasEscaped(scene_, bodies.position(i))) ++result.escaped;
      if (!bodies.awake(i)) ++result.asleep;
    }
    if (scene_.top_body >= 0) {
      const Vec3& start = scene_.bodies[static_cast<std::size_t>(scene_.top_body)].position;
      const Vec3& now =
          bodies.position(*bodies.find(ids_[static_cast<std::size_t>(scene_.top_body)]));
      result.top_drop = start.z() - now.z();
      result.top_distance = (start - now).norm();
    }
    for (const engine::BodyContactReport& contact : world_.bodyContacts()) {
      result.contacts += static_cast<int>(contact.points.size());
    }
    result.max_penetration = deepestOverlap();
    return result;
  }

  Vec3 position(const std::size_t k) const {
    const engine::BodyStore& bodies = world_.bodies();
    return bodies.position(*bodies.find(ids_[k]));
  }

  Vec3 linearVelocity(const std::size_t k) const {
    const engine::BodyStore& bodies = world_.bodies();
    return bodies.linearVelocity(*bodies.find(ids_[k]));
  }

  // m v^2 / 2 + w_b . I w_b / 2, w_b the angular velocity in the body's principal frame.
  double kineticEnergy(const std::size_t k) const {
    const engine::BodyStore& bodies = world_.bodies();
    const std::size_t i = *bodies.find(ids_[k]);
    const Vec3 w = bodies.orientation(i).conjugate() * bodies.angularVelocity(i);
    return 0.5 * (bodies.mass(i) * bodies.linearVelocity(i).squaredNorm() +
                  w.dot(bodies.principalInertia(i).cwiseProduct(w)));
  }

  double deepestOverlap() const {
    double deepest = 0.0;
    for (const engine::BodyContactReport& contact : world_.bodyContacts()) {
      for (const auto& point : contact.points) deepest = std::max(deepest, -point.separation);
    }
    return deepest;
  }

 private:
  const RigidScene& scene_;
  engine::World world_;
  std::vector<BodyId> ids_;
};

void runScene(benchmark::State& state, const RigidScene& scene) {
  const auto substeps = static_cast<int>(state.range(1));
  const bool sleeping = state.range(2) != 0;
  const auto iterations = static_cast<int>(state.range(3));
  state.SetLabel(scene.name + (sleeping ? ", sleeping" : ", sleeping off"));

  EngineWorld world(scene, substeps, iterations, sleeping);
  const Settled settled = settle(world, scene);
  const AtRest at_rest = world.atRest();

  for (auto _ : state) {
    world.stepFrame();
    benchmark::ClobberMemory();
  }

  reportAtRest(state, scene, at_rest, settled);
}

// Substeps 1 and 4 (the default) of 2 iterations, sleeping off and on; `kFrames` timed frames
// each.
template <int kSize, int kFrames>
void runs(benchmark::internal::Benchmark* b) {
  for (const int sleeping : {0, 1}) {
    for (const int substeps : {1, 4}) b->Args({kSize, substeps, sleeping, 2});
  }
  b->Iterations(kFrames)->Unit(benchmark::kMillisecond);
}

// The same and 8 and 12 substeps of 1 iteration.
template <int kSize, int kFrames>
void pileRuns(benchmark::internal::Benchmark* b) {
  runs<kSize, kFrames>(b);
  for (const int substeps : {8, 12}) {
    for (const int sleeping : {0, 1}) b->Args({kSize, substeps, sleeping, 1});
  }
}

// The same and 4 substeps of 3 and 4 iterations, sleeping off: what a pile of small mixed boxes
// needs to rest as shallow as Bullet's (docs/BENCHMARKS.md).
template <int kSize, int kFrames>
void dropRuns(benchmark::internal::Benchmark* b) {
  runs<kSize, kFrames>(b);
  for (const int iterations : {3, 4}) b->Args({kSize, 4, 0, iterations});
}

// The quality ladder, sleeping off: the cheaper settings, to find the least that reaches a given
// at-rest quality (docs/BENCHMARKS.md, "equal quality"); bullet_peer_bench.cpp climbs Bullet's.
template <int kSize>
void ladderRuns(benchmark::internal::Benchmark* b) {
  b->Args({kSize, 1, 0, 1})->Args({kSize, 2, 0, 1})->Args({kSize, 2, 0, 2});
}

void BM_RigidPyramid(benchmark::State& state) {
  runScene(state, pyramid(static_cast<int>(state.range(0))));
}
void BM_RigidDroppedPyramid(benchmark::State& state) {
  runScene(state, droppedPyramid(static_cast<int>(state.range(0))));
}
void BM_RigidPyramidAndRoller(benchmark::State& state) {
  runScene(state, pyramidAndRoller(static_cast<int>(state.range(0))));
}
void BM_RigidStack(benchmark::State& state) {
  runScene(state, stack(static_cast<int>(state.range(0))));
}
void BM_RigidRandomDrop(benchmark::State& state) {
  runScene(state,
           randomDrop(static_cast<int>(state.range(0)), benchmarkSeed(kRandomDropDefaultSeed)));
}
void BM_RigidParticleRain(benchmark::State& state) {
  runScene(state, particleRain(static_cast<int>(state.range(0)), benchmarkSeed(kRainDefaultSeed)));
}

BENCHMARK(BM_RigidPyramid)->Apply(runs<20, 600>)->Apply(ladderRuns<20>)->Args({20, 8, 0, 1});
BENCHMARK(BM_RigidPyramid)->Apply(pileRuns<100, 60>)->Apply(ladderRuns<100>);
BENCHMARK(BM_RigidDroppedPyramid)->Apply(runs<20, 600>)->Apply(ladderRuns<20>)->Args({20, 8, 0, 1});
BENCHMARK(BM_RigidPyramidAndRoller)
    ->Args({100, 4, 1, 2})
    ->Iterations(60)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RigidStack)->Apply(runs<10, 600>)->Apply(ladderRuns<10>);
BENCHMARK(BM_RigidStack)->Apply(runs<20, 600>)->Apply(ladderRuns<20>);
BENCHMARK(BM_RigidRandomDrop)->Apply(dropRuns<1000, 300>)->Apply(ladderRuns<1000>);
BENCHMARK(BM_RigidParticleRain)
    ->Apply(runs<kRainDefaultSpheres, 300>)
    ->Apply(ladderRuns<kRainDefaultSpheres>);

}  // namespace
}  // namespace rigid
}  // namespace bench
}  // namespace mass_aggregate_sim
