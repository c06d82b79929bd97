// The two halves of a published frame, on the scene of test/publish_thread.test (10,000 free
// grains, ~markers and ~particles subscribed): what the world thread does (copy the world into a
// frame) against what the publishing thread does (build each message and serialise it, as
// roscpp does for a subscriber in another process). The world thread pays only the first.
#include <benchmark/benchmark.h>
#include <ros/serialization.h>

#include <stdexcept>

#include "mass_aggregate_sim/node/conversions.h"
#include "mass_aggregate_sim/node/markers.h"
#include "mass_aggregate_sim/node/snapshot.h"

namespace mass_aggregate_sim {
namespace node {
namespace {

engine::World fallingGrains(const int side) {
  engine::World world;
  engine::ParticleSpec spec;
  spec.inverse_mass = 100.0;
  spec.radius = 0.05;
  for (int i = 0; i < side; ++i) {
    for (int j = 0; j < side; ++j) {
      spec.position = engine::Vec3(-5.0 + 0.1 * i, -5.0 + 0.1 * j, 100.0);
      if (!world.addParticle(spec)) throw std::runtime_error("grain rejected");
    }
  }
  world.step();
  return world;
}

void BM_FrameCopy(benchmark::State& state) {
  const engine::World world = fallingGrains(static_cast<int>(state.range(0)));
  WorldSnapshot snapshot;
  for (auto _ : state) {
    takeSnapshot(world, snapshot);
    benchmark::DoNotOptimize(snapshot.positions.data());
  }
  state.counters["particles"] = static_cast<double>(world.particles().size());
}
BENCHMARK(BM_FrameCopy)->Arg(100)->Unit(benchmark::kMicrosecond);

void BM_FramePublish(benchmark::State& state) {
  const engine::World world = fallingGrains(static_cast<int>(state.range(0)));
  WorldSnapshot snapshot;
  takeSnapshot(world, snapshot);
  MarkerBuilder markers("world", 10.0);
  std::size_t bytes = 0;
  for (auto _ : state) {
    ParticleArray particles;
    particles.header.frame_id = "world";
    fillParticleArray(snapshot, particles);
    const ros::SerializedMessage particles_wire = ros::serialization::serializeMessage(particles);
    const visualization_msgs::MarkerArray array =
        markers.build(snapshot, world.colliders(), ros::Time(1.0));
    const ros::SerializedMessage markers_wire = ros::serialization::serializeMessage(array);
    bytes = particles_wire.num_bytes + markers_wire.num_bytes;
    benchmark::DoNotOptimize(bytes);
  }
  state.counters["bytes"] = static_cast<double>(bytes);
}
BENCHMARK(BM_FramePublish)->Arg(100)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace node
}  // namespace mass_aggregate_sim

BENCHMARK_MAIN();
