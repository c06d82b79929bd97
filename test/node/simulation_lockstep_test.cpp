// Determinism at the node's level: two Simulation objects given the same requests stay
// bit-identical whether one runs step by step (the node running) and the other in ~step blocks
// (the node paused), with sustained forces spanning the blocks, and again after a reset.
#include <gtest/gtest.h>

#include <functional>
#include <vector>

#include "mass_aggregate_sim/node/scene_loader.h"
#include "mass_aggregate_sim/node/simulation.h"
#include "yaml_to_xmlrpc.h"

namespace mass_aggregate_sim {
namespace node {
namespace {

using engine::Vec3;

engine::World lockstepScene() {
  const auto loaded = loadScene(test::yamlToXmlRpc(R"(
rate: 120
substeps: 2
collisions: {particle_collisions: true}
colliders: [{type: plane, normal: [0, 0, 1], offset: 0}]
lines:
  - {name: chain, start: [-1, 0, 2], end: [0, 0, 2], count: 6, mass: 0.5, fixed_indices: [0],
     link: {type: spring, stiffness: 200, damping: 0.5}}
blocks:
  - {name: grain, origin: [1, 0, 0.3], count: [3, 3, 2], spacing: 0.21, jitter: 0.003,
     mass: 0.1, radius: 0.1}
)"),
                                SceneOverrides{});
  EXPECT_TRUE(loaded.isOk()) << loaded.message();
  return loaded.value().world;
}

// The requests, with a hook that advances n steps in between (one by one, or at once).
void drive(Simulation& sim, const std::function<void(Simulation&, std::uint32_t)>& advance) {
  advance(sim, 30);
  ASSERT_TRUE(sim.spawn({[] {
    engine::ParticleSpec s;
    s.name = "probe";
    s.inverse_mass = 2.0;
    s.radius = 0.1;
    s.position = Vec3(1.2, 0.2, 1.5);
    return s;
  }()}));
  ASSERT_TRUE(sim.applyForce({{0, "probe"}, Vec3(0, 0, 15), ForceMode::kDuration, 0.2}));
  ASSERT_TRUE(sim.applyForce({{0, "chain_5"}, Vec3(1, 0, 0), ForceMode::kUntilCleared, 0.0}));
  advance(sim, 17);  // the DURATION force (24 steps) spans this block and the next
  ASSERT_TRUE(sim.applyImpulse({0, "grain_4"}, Vec3(0.05, 0, 0.1)));
  advance(sim, 40);
  ASSERT_TRUE(sim.applyForce({{0, "chain_5"}, Vec3::Zero(), ForceMode::kClear, 0.0}));
  LinkRequest link;
  link.a.name = "probe";
  link.b = ParticleRef{0, "chain_5"};
  link.stiffness = 20.0;
  const auto id = sim.addLink(link);
  ASSERT_TRUE(id.isOk());
  advance(sim, 25);
  ASSERT_TRUE(sim.setState({0, "grain_0"}, Vec3(1.0, 0.0, 0.8), Vec3(0, 0, -1)));
  ASSERT_TRUE(sim.removeLink(*id));
  ASSERT_TRUE(sim.remove({{0, "grain_7"}}));
  advance(sim, 33);
}

TEST(SimulationLockstepTest, RunningAndPausedSteppingGiveTheSameBits) {
  const engine::World scene = lockstepScene();
  Simulation running(scene, SimulationLimits{});
  Simulation paused(scene, SimulationLimits{});
  std::vector<std::uint64_t> trace;
  drive(running, [&](Simulation& s, const std::uint32_t n) {
    for (std::uint32_t i = 0; i < n; ++i) {
      s.step();
      trace.push_back(s.world().stateHash());
    }
  });
  int blocks = 0;
  drive(paused, [&](Simulation& s, const std::uint32_t n) {
    ASSERT_TRUE(s.stepMany(n));
    ASSERT_LE(s.world().stepCount(), trace.size());
    EXPECT_EQ(s.world().stateHash(), trace[s.world().stepCount() - 1])
        << "at step " << s.world().stepCount();
    ++blocks;
  });
  EXPECT_EQ(blocks, 5);
  EXPECT_EQ(running.world().stepCount(), 145u);
  EXPECT_EQ(running.world().stateHash(), paused.world().stateHash());
  EXPECT_EQ(running.sustainedForceCount(), paused.sustainedForceCount());
}

TEST(SimulationLockstepTest, AfterAResetTheSameRequestsGiveTheSameBits) {
  const engine::World scene = lockstepScene();
  Simulation sim(scene, SimulationLimits{});
  const auto blocks = [](Simulation& s, const std::uint32_t n) { ASSERT_TRUE(s.stepMany(n)); };
  drive(sim, blocks);
  const std::uint64_t first = sim.world().stateHash();
  // A sustained force still active at the reset must not survive it.
  ASSERT_TRUE(sim.applyForce({{0, "probe"}, Vec3(3, 0, 0), ForceMode::kUntilCleared, 0.0}));
  sim.reset();
  EXPECT_EQ(sim.world().stateHash(), scene.stateHash());
  drive(sim, blocks);
  EXPECT_EQ(sim.world().stateHash(), first);
  Simulation fresh(scene, SimulationLimits{});
  drive(fresh, blocks);
  EXPECT_EQ(fresh.world().stateHash(), first);
}

}  // namespace
}  // namespace node
}  // namespace mass_aggregate_sim
