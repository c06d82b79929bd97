// Determinism: a fixed scene (springs, a ground plane, particle collisions) stepped a fixed
// number of times gives a stated state hash, and two worlds driven by the same calls in the same
// order stay bit-identical, across step-at-once and across a reset of the calls.
//
// kGoldenHash depends on the exact floating-point operations of a step. Any change to the
// integration or contact arithmetic (operation order, a new term, another compiler or
// -march/-ffp-contract setting) changes it; that is what the test is for. When such a change is
// intended, run
//   devel/lib/mass_aggregate_sim/engine_tests --gtest_filter='GoldenHash.*'
// read the "[ golden ] hash" line it prints, and replace kGoldenHash with it, saying why in the
// commit message. On x86-64 the normal build runs the AVX2 versions of the SIMD loops (simd.h) and
// the sanitizer build (scripts/sanitizer_tests.sh) the baseline ones; both must give this hash.
#include <gtest/gtest.h>

#include <cstdio>
#include <functional>
#include <vector>

#include "../integrators/integrator_params.h"
#include "mass_aggregate_sim/engine/world/world.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

constexpr std::uint64_t kGoldenHash = 0xbf63a3472c00d5f8ull;
constexpr int kGoldenSteps = 600;

// A hanging spring chain, a falling 3 x 3 x 2 block of grains and a ground plane: springs,
// plane contacts and particle-particle contacts all act within the first 600 steps.
World goldenScene(const Integrator integrator = Integrator::kSemiImplicitEuler) {
  WorldConfig config;
  config.dt = 1.0 / 120.0;
  config.substeps = 2;
  config.integrator = integrator;
  config.gravity = Vec3(0.0, 0.0, -9.81);
  World world(config);
  CollisionSettings collisions;
  collisions.particle_collisions = true;
  collisions.particle_restitution = 0.3;
  collisions.particle_friction = 0.2;
  EXPECT_TRUE(world.setCollisionSettings(collisions));
  PlaneCollider ground;
  ground.material.restitution = 0.2;
  ground.material.friction = 0.5;
  EXPECT_TRUE(world.addCollider(ground).isOk());

  ParticleSpec spec;
  spec.radius = 0.05;
  spec.damping = 0.98;
  std::vector<ParticleId> chain;
  for (int i = 0; i < 6; ++i) {
    spec.position = Vec3(-1.0 + 0.2 * i, 0.0, 2.0);
    spec.inverse_mass = i == 0 ? 0.0 : 2.0;
    chain.push_back(*world.addParticle(spec));
  }
  for (int i = 0; i + 1 < 6; ++i) {
    EXPECT_TRUE(
        world.addGenerator(Spring::between(chain[i], chain[i + 1], 200.0, 0.2, 0.5)).isOk());
  }
  EXPECT_TRUE(
      world.addGenerator(Spring::anchoredAt(chain[5], Vec3(0.5, 0.0, 2.5), 30.0, 0.6, 0.1)).isOk());
  spec.radius = 0.1;
  spec.inverse_mass = 10.0;
  for (int z = 0; z < 2; ++z) {
    for (int y = 0; y < 3; ++y) {
      for (int x = 0; x < 3; ++x) {
        // Offsets of a few mm so the stack is not perfectly symmetric.
        spec.position = Vec3(1.0 + 0.21 * x + 0.003 * z, 0.21 * y - 0.002 * x, 0.3 + 0.22 * z);
        world.addParticle(spec);
      }
    }
  }
  return world;
}

void stepN(World& world, const int n) {
  for (int i = 0; i < n; ++i) world.step();
}

TEST(GoldenHash, FixedSceneGivesTheStatedHash) {
  World world = goldenScene();
  stepN(world, kGoldenSteps);
  std::printf("[ golden ] hash 0x%016llx after %d steps\n",
              static_cast<unsigned long long>(world.stateHash()), kGoldenSteps);
  EXPECT_EQ(world.divergenceCount(), 0u);
  // The scene really has contacts at the end: grains resting on the plane and on each other.
  EXPECT_GT(world.lastContactStats().contacts, 9u);
  EXPECT_EQ(world.stateHash(), kGoldenHash) << "integration arithmetic changed; see the comment "
                                               "at the top of golden_hash_test.cpp";
}

// The same calls, interleaved with steps: impulses, forces, teleports, removals and additions.
void drive(World& world, const std::function<void(World&, int)>& step_block) {
  const ParticleId second = world.particles().idAt(1);
  const ParticleId grain = world.particles().idAt(7);
  step_block(world, 50);
  EXPECT_TRUE(world.applyImpulse(second, Vec3(0.3, 0.0, 0.4)));
  step_block(world, 37);
  EXPECT_TRUE(world.addForce(grain, Vec3(0.0, 2.0, 5.0)));
  step_block(world, 1);
  EXPECT_TRUE(world.setVelocity(grain, Vec3(-1.0, 0.0, 2.0)));
  step_block(world, 60);
  EXPECT_TRUE(world.removeParticle(world.particles().idAt(10)));
  ParticleSpec extra;
  extra.position = Vec3(1.2, 0.1, 1.5);
  extra.radius = 0.1;
  extra.inverse_mass = 5.0;
  EXPECT_TRUE(world.addParticle(extra).isOk());
  step_block(world, 90);
  EXPECT_TRUE(world.setPosition(second, Vec3(-0.8, 0.05, 1.9)));
  step_block(world, 33);
}

class Lockstep : public ::testing::TestWithParam<Integrator> {};

TEST_P(Lockstep, TwoWorldsWithTheSameCallsStayBitIdentical) {
  World a = goldenScene(GetParam());
  World b = goldenScene(GetParam());
  ASSERT_EQ(a.stateHash(), b.stateHash());
  // a steps one at a time and keeps the hash after every step; b takes each block at once (as
  // the node does for a ~step request while paused) and must match a at every block's end.
  std::vector<std::uint64_t> trace;
  drive(a, [&](World& w, const int n) {
    for (int i = 0; i < n; ++i) {
      w.step();
      trace.push_back(w.stateHash());
    }
  });
  int blocks = 0;
  drive(b, [&](World& w, const int n) {
    stepN(w, n);
    ASSERT_LE(w.stepCount(), trace.size());
    EXPECT_EQ(w.stateHash(), trace[w.stepCount() - 1]) << "at step " << w.stepCount();
    ++blocks;
  });
  EXPECT_EQ(blocks, 6);
  EXPECT_EQ(a.stepCount(), b.stepCount());
  EXPECT_EQ(a.stateHash(), b.stateHash());
}

TEST_P(Lockstep, AResetWorldRepeatsItselfBitForBit) {
  const World scene = goldenScene(GetParam());
  World world = scene;
  const auto blocks = [](World& w, const int n) { stepN(w, n); };
  drive(world, blocks);
  const std::uint64_t first = world.stateHash();
  const std::uint64_t first_steps = world.stepCount();
  // Reset as the node does (copy the loaded scene back), then the same calls again.
  world = scene;
  EXPECT_EQ(world.stateHash(), scene.stateHash());
  drive(world, blocks);
  EXPECT_EQ(world.stepCount(), first_steps);
  EXPECT_EQ(world.stateHash(), first);
  // And a world that never ran agrees too: nothing of the first run survived the reset.
  World fresh = scene;
  drive(fresh, blocks);
  EXPECT_EQ(fresh.stateHash(), first);
}

INSTANTIATE_TEST_SUITE_P(EveryIntegrator, Lockstep, everyIntegrator(), integratorParamName);

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
