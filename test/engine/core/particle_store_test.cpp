#include <gtest/gtest.h>

#include <cstdint>
#include <optional>
#include <random>
#include <vector>

#include "mass_aggregate_sim/engine/world/world.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

ParticleSpec specAt(const Real x, const std::string& name = {}) {
  ParticleSpec spec;
  spec.position = Vec3(x, 0.0, 0.0);
  spec.name = name;
  return spec;
}

TEST(ParticleStore, IdsStayValidAcrossManyAddRemoveCycles) {
  ParticleStore store;
  std::vector<std::pair<ParticleId, Real>> live;
  std::vector<ParticleId> removed;
  std::mt19937 rng(42);
  for (int cycle = 0; cycle < 20000; ++cycle) {
    if (live.empty() || rng() % 3 != 0) {
      const Real x = static_cast<Real>(cycle);
      live.emplace_back(store.add(specAt(x)), x);
    } else {
      const std::size_t pick = rng() % live.size();
      ASSERT_TRUE(store.remove(live[pick].first).isOk());
      removed.push_back(live[pick].first);
      live[pick] = live.back();
      live.pop_back();
    }
  }
  ASSERT_EQ(store.size(), live.size());
  for (const auto& [id, x] : live) {
    const auto dense = store.find(id);
    ASSERT_TRUE(dense.has_value());
    EXPECT_EQ(store.positions()(0, static_cast<Eigen::Index>(*dense)), x);
    EXPECT_EQ(store.idAt(*dense), id);
  }
  for (const ParticleId& id : removed) {
    EXPECT_FALSE(store.contains(id)) << id.str();
  }
}

TEST(ParticleStore, StaleIdIsDetectedAndReported) {
  ParticleStore store;
  const ParticleId first = store.add(specAt(1.0));
  ASSERT_TRUE(store.remove(first).isOk());
  const ParticleId second = store.add(specAt(2.0));
  EXPECT_EQ(second.index, first.index);            // the slot is reused ...
  EXPECT_NE(second.generation, first.generation);  // ... under a new generation
  EXPECT_FALSE(store.contains(first));
  const Status again = store.remove(first);
  EXPECT_FALSE(again.isOk());
  EXPECT_NE(again.message().find("stale"), std::string::npos) << again.message();
  EXPECT_TRUE(store.contains(second));
  EXPECT_EQ(store.size(), 1u);
  EXPECT_FALSE(store.remove(ParticleId{}).isOk());
  EXPECT_FALSE(store.remove(ParticleId{99, 0}).isOk());
}

TEST(ParticleStore, RemovingKeepsOtherParticlesAttributes) {
  ParticleStore store;
  const ParticleId a = store.add(specAt(1.0, "a"));
  const ParticleId b = store.add(specAt(2.0, "b"));
  const ParticleId c = store.add(specAt(3.0, "c"));
  ASSERT_TRUE(store.remove(a).isOk());
  EXPECT_EQ(store.positions()(0, static_cast<Eigen::Index>(*store.find(c))), 3.0);
  EXPECT_EQ(store.name(*store.find(c)), "c");
  EXPECT_EQ(store.name(*store.find(b)), "b");
  EXPECT_EQ(store.findByName("c"), c);
  EXPECT_FALSE(store.findByName("a").has_value());
}

// The vectorised passes load 32 bytes at a time: every array starts on a cache line, whatever
// the heap did before, through every reallocation as the store grows.
TEST(ParticleStore, EveryArrayStartsOnACacheLine) {
  const auto on_line = [](const void* p) { return reinterpret_cast<std::uintptr_t>(p) % 64 == 0; };
  ParticleStore store;
  std::vector<std::vector<char>> heap_noise;
  for (int i = 0; i < 300; ++i) {
    heap_noise.emplace_back(static_cast<std::size_t>(8 + 24 * (i % 7)));  // shifts later blocks
    store.add(ParticleSpec{});
    const ParticleStore& read = store;
    ASSERT_TRUE(on_line(store.positions().data())) << i;
    ASSERT_TRUE(on_line(store.velocities().data())) << i;
    ASSERT_TRUE(on_line(store.forces().data())) << i;
    ASSERT_TRUE(on_line(store.accelerations().data())) << i;
    ASSERT_TRUE(on_line(store.previousPositions().data())) << i;
    ASSERT_TRUE(on_line(store.previousExternalAccelerations().data())) << i;
    ASSERT_TRUE(on_line(store.historySeeded().data())) << i;
    ASSERT_TRUE(on_line(read.inverseMasses().data())) << i;
    ASSERT_TRUE(on_line(read.mobility().data())) << i;
    ASSERT_TRUE(on_line(read.dampings().data())) << i;
    ASSERT_TRUE(on_line(store.radii().data())) << i;
  }
}

TEST(ParticleStore, PackedIdRoundTrips) {
  const ParticleId id{123, 456};
  EXPECT_EQ(ParticleId::fromPacked(id.packed()), id);
}

TEST(ParticleSpecValidation, RefusesBadValues) {
  ParticleSpec spec;
  EXPECT_TRUE(validateSpec(spec).isOk());
  spec.inverse_mass = -1.0;
  EXPECT_FALSE(validateSpec(spec).isOk());
  spec = ParticleSpec{};
  spec.position.x() = std::numeric_limits<Real>::quiet_NaN();
  EXPECT_FALSE(validateSpec(spec).isOk());
  spec = ParticleSpec{};
  spec.damping = 1.5;
  EXPECT_FALSE(validateSpec(spec).isOk());
  spec = ParticleSpec{};
  spec.radius = -0.1;
  EXPECT_FALSE(validateSpec(spec).isOk());
  spec = ParticleSpec{};
  spec.velocity.y() = std::numeric_limits<Real>::infinity();
  EXPECT_FALSE(validateSpec(spec).isOk());
}

// The semi-implicit Euler pass reads own accelerations only when some particle has one: the
// count must follow the particle that has it through removals that move it, and -0 counts.
TEST(ParticleStore, OwnAccelerationsAreCountedThroughAddRemoveAndClear) {
  ParticleStore store;
  ParticleSpec plain;
  ParticleSpec pushed;
  pushed.acceleration = Vec3(0.0, 5.0, 0.0);
  ParticleSpec negative_zero;
  negative_zero.acceleration = Vec3(0.0, -0.0, 0.0);
  const ParticleId first = store.add(plain);
  EXPECT_FALSE(store.anyOwnAcceleration());
  const ParticleId second = store.add(plain);
  const ParticleId last = store.add(pushed);
  EXPECT_TRUE(store.anyOwnAcceleration());
  ASSERT_TRUE(store.remove(first).isOk());  // `last` moves into the hole
  ASSERT_EQ(store.find(last), std::optional<std::size_t>(0));
  EXPECT_TRUE(store.anyOwnAcceleration());
  ASSERT_TRUE(store.remove(second).isOk());
  EXPECT_TRUE(store.anyOwnAcceleration());
  ASSERT_TRUE(store.remove(last).isOk());
  EXPECT_FALSE(store.anyOwnAcceleration());
  store.add(negative_zero);
  EXPECT_TRUE(store.anyOwnAcceleration());
  store.add(pushed);
  store.clear();
  EXPECT_FALSE(store.anyOwnAcceleration());
  store.add(plain);
  EXPECT_FALSE(store.anyOwnAcceleration());
}

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
