// The caches the step keeps for speed must not change the motion: springs with dense indices
// (rebuilt when the store's layout changes) and the forces the energy guard evaluates ahead for
// the next semi-implicit Euler step (dropped whenever the scene changes between steps).
#include <gtest/gtest.h>

#include <algorithm>

#include "engine/forces/spring_runs.h"
#include "mass_aggregate_sim/engine/world/world.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

// Two damped chains of springs and bungees, an anchored spring and a stiff spring, under gravity.
std::vector<ParticleId> buildScene(World& world) {
  std::vector<ParticleId> ids;
  for (int c = 0; c < 2; ++c) {
    for (int j = 0; j < 10; ++j) {
      ParticleSpec spec;
      spec.position = Vec3(j, 0.1 * (j % 3), 2.0 * c);
      spec.damping = 0.9;
      spec.inverse_mass = 1.0 / (1.0 + 0.1 * j);
      ids.push_back(*world.addParticle(spec));
      if (j == 0) continue;
      const ParticleId a = ids[ids.size() - 2];
      const ParticleId b = ids.back();
      if (j % 3 == 0) {
        EXPECT_TRUE(world.addGenerator(Spring::between(a, b, 40.0, 0.9, 0.5).pullingOnly()).isOk());
      } else {
        EXPECT_TRUE(world.addGenerator(Spring::between(a, b, 30.0, 1.0, 0.2)).isOk());
      }
    }
  }
  EXPECT_TRUE(world.addGenerator(Spring::anchoredAt(ids[0], Vec3(0, 1, 0), 20.0, 0.5, 0.1)).isOk());
  EXPECT_TRUE(world.addGenerator(StiffSpring{ids[10], Vec3(0, 1, 2), 500.0, 1.0}).isOk());
  return ids;
}

World makeWorld(const Real energy_growth_limit) {
  WorldConfig config;
  config.integrator = Integrator::kSemiImplicitEuler;
  config.gravity = Vec3(0.0, -9.81, 0.0);
  config.energy_growth_limit = energy_growth_limit;
  return World(config);
}

// The guard on (forces evaluated ahead) and off (forces evaluated in the step) give bit-identical
// states, also across every kind of change between steps.
TEST(StepCache, EnergyGuardDoesNotChangeTheMotion) {
  World guarded = makeWorld(10.0);
  World plain = makeWorld(0.0);
  const std::vector<ParticleId> ids = buildScene(guarded);
  ASSERT_EQ(buildScene(plain), ids);
  for (int s = 0; s < 400; ++s) {
    for (World* world : {&guarded, &plain}) {
      switch (s) {
        case 50:
          ASSERT_TRUE(world->setPosition(ids[4], Vec3(4.0, 0.5, 0.0)).isOk());
          break;
        case 100:
          ASSERT_TRUE(world->setVelocity(ids[12], Vec3(0.0, 3.0, 0.0)).isOk());
          break;
        case 150:
          ASSERT_TRUE(world->applyImpulse(ids[15], Vec3(1.0, 0.0, 0.0)).isOk());
          break;
        case 200:
          // Moves the last particle into the hole: dense indices change.
          ASSERT_TRUE(world->removeParticle(ids[5]).isOk());
          break;
        case 250:
          ASSERT_TRUE(world->addGenerator(Spring::between(ids[3], ids[14], 10.0, 2.0, 0.0)).isOk());
          break;
        case 300:
          ASSERT_TRUE(world->addForce(ids[7], Vec3(0.0, 50.0, 0.0)).isOk());
          break;
        case 350: {
          WorldConfig config = world->config();
          config.dt = 1.0 / 120.0;
          ASSERT_TRUE(world->setConfig(config).isOk());
          break;
        }
        default:
          break;
      }
      world->step();
    }
    ASSERT_EQ(guarded.stateHash(), plain.stateHash()) << "step " << s;
  }
  EXPECT_EQ(guarded.divergenceCount(), 0u);
  EXPECT_EQ(plain.divergenceCount(), 0u);
}

// The forces of the dense springs from the run kernels (four springs at a time) and from the
// scattered path (one spring at a time) are the same to the bit, and the elastic energy the force
// pass makes matches the energy computed alone.
void expectRunsMatchTheScatteredPath(const ParticleStore& particles, const DenseSprings& dense) {
  DenseSprings scattered = dense;
  for (SpringSegment& segment : scattered.pair_segments) segment.run = false;
  for (SpringSegment& segment : scattered.pull_pair_segments) segment.run = false;
  const Eigen::Index n = static_cast<Eigen::Index>(particles.size());
  Vec3Array by_runs = Vec3Array::Zero(3, n);
  Vec3Array one_by_one = Vec3Array::Zero(3, n);
  Real elastic = 0.0;
  accumulateDenseSprings(dense, particles.positions(), particles.velocities(), by_runs, &elastic);
  accumulateDenseSprings(scattered, particles.positions(), particles.velocities(), one_by_one,
                         nullptr);
  for (Eigen::Index i = 0; i < n; ++i) {
    for (int c = 0; c < 3; ++c) {
      ASSERT_EQ(by_runs(c, i), one_by_one(c, i)) << "particle " << i << " component " << c;
    }
  }
  EXPECT_GT(by_runs.cwiseAbs().maxCoeff(), 0.0);
  const Real energy = denseSpringEnergy(scattered, particles.positions());
  EXPECT_GT(energy, 0.0);
  EXPECT_NEAR(elastic, energy, 1e-12 * energy);
}

// Springs resolved to dense indices after a removal
// reordered the store, and so does the elastic energy of the springs.
TEST(StepCache, DenseSpringsMatchIdLookupsAfterARemoval) {
  ParticleStore particles;
  ForceGenerators generators;
  std::vector<ParticleId> ids;
  for (int i = 0; i < 8; ++i) {
    ParticleSpec spec;
    spec.position = Vec3(1.1 * i, 0.2 * (i % 2), 0.05 * i * i);
    spec.velocity = Vec3(0.0, 0.3 * i, -0.1 * i);
    ids.push_back(particles.add(spec));
  }
  ASSERT_TRUE(particles.remove(ids[2]).isOk());
  for (int i = 3; i < 7; ++i) {
    generators.of<Spring>().push_back(Spring::between(ids[i], ids[i + 1], 5.0 + i, 1.0, 0.3));
    generators.of<Spring>().push_back(
        Spring::between(ids[i + 1], ids[i], 7.0, 0.5, 0.1).pullingOnly());
  }
  generators.of<Spring>().push_back(Spring::between(ids[0], ids[7], 2.0, 3.0, 0.0));
  expectRunsMatchTheScatteredPath(particles,
                                  resolveDenseSprings(generators.of<Spring>(), particles));
}

// A cloth whose rows and columns make runs (ends advancing together, some given b before a, some
// damped), bungees slack and taut, and a removal that breaks one run: the run kernels give the
// forces of the id look-ups bit for bit, and the elastic energy.
TEST(StepCache, SpringRunsMatchIdLookups) {
  constexpr int kWidth = 12;
  constexpr int kHeight = 9;
  ParticleStore particles;
  ForceGenerators generators;
  std::vector<ParticleId> ids;
  for (int i = 0; i < kWidth * kHeight; ++i) {
    ParticleSpec spec;
    const int row = i / kWidth;
    const int col = i % kWidth;
    spec.position = Vec3(1.05 * col + 0.01 * row * row, 0.93 * row, 0.03 * ((i * 7) % 5));
    spec.velocity = Vec3(0.1 * (i % 4), -0.2 * (i % 3), 0.05 * row);
    ids.push_back(particles.add(spec));
  }
  const auto at = [&ids](const int row, const int col) { return ids[row * kWidth + col]; };
  for (int row = 0; row < kHeight; ++row) {
    for (int col = 0; col + 1 < kWidth; ++col) {
      const Real damping = row % 2 == 0 ? 0.0 : 0.4;
      if (row % 3 == 2) {
        generators.of<Spring>().push_back(
            Spring::between(at(row, col + 1), at(row, col), 20.0, 1.0, damping));
      } else {
        generators.of<Spring>().push_back(
            Spring::between(at(row, col), at(row, col + 1), 20.0, 1.0, damping));
      }
    }
  }
  for (int row = 0; row + 1 < kHeight; ++row) {
    for (int col = 0; col < kWidth; ++col) {
      generators.of<Spring>().push_back(
          Spring::between(at(row, col), at(row + 1, col), 15.0, 0.9, 0.0));
      // Rest length 0.93 or 0.95 against row spacings near 0.93: some slack, some taut.
      generators.of<Spring>().push_back(
          Spring::between(at(row, col), at(row + 1, col), 9.0, col % 2 == 0 ? 0.93 : 0.95, 0.1)
              .pullingOnly());
    }
  }
  ParticleSpec extra;
  extra.position = Vec3(3.0, 3.0, 3.0);
  const ParticleId loose = particles.add(extra);
  generators.of<Spring>().push_back(Spring::between(loose, ids[5], 4.0, 0.5, 0.2));
  // Broken links aside, removing a particle moves the last one into its slot.
  ASSERT_TRUE(particles.remove(ids.back()).isOk());
  generators.of<Spring>().erase(
      std::remove_if(generators.of<Spring>().begin(), generators.of<Spring>().end(),
                     [&](const Spring& s) { return s.a == ids.back() || s.b == ids.back(); }),
      generators.of<Spring>().end());
  const DenseSprings dense = resolveDenseSprings(generators.of<Spring>(), particles);
  const auto runs = [](const std::vector<SpringSegment>& segments) {
    return std::count_if(segments.begin(), segments.end(),
                         [](const SpringSegment& s) { return s.run; });
  };
  EXPECT_GE(runs(dense.pair_segments), kHeight + 1);
  EXPECT_GE(runs(dense.pull_pair_segments), 1);
  std::size_t covered = 0;
  for (const SpringSegment& s : dense.pair_segments) {
    EXPECT_EQ(s.first, covered);
    covered += s.count;
  }
  EXPECT_EQ(covered, dense.pairs.size());
  expectRunsMatchTheScatteredPath(particles, dense);
}

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
