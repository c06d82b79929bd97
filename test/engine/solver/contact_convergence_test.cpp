// How fast and how well the resolver settles piles: resting contacts follow their impulses in
// position, warm-started normal and friction impulses, the velocity tolerance, and the dense grid.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "../integrators/integrator_params.h"
#include "engine/collision/broadphase.h"
#include "mass_aggregate_sim/engine/world/world.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

constexpr Real kRadius = 0.1;

// A side x side x layers cubic lattice of touching spheres (1 kg, radius 0.1) on the ground z = 0,
// boxed in by four walls touching the outer spheres.
World latticePile(const int side, const int layers, const Integrator integrator,
                  const Real friction = 0.0) {
  WorldConfig config;
  config.gravity = Vec3(0.0, 0.0, -9.81);
  config.integrator = integrator;
  World world(config);
  CollisionSettings settings;
  settings.particle_collisions = true;
  settings.broadphase = Broadphase::kUniformGrid;
  settings.particle_restitution = 0.2;
  settings.particle_friction = friction;
  EXPECT_TRUE(world.setCollisionSettings(settings).isOk());
  const Real spacing = 2.0 * kRadius;
  const Real half_width = 0.5 * spacing * side;
  const Material material{0.2, friction};
  EXPECT_TRUE(world.addCollider(PlaneCollider{Vec3::UnitZ(), 0.0, material}).isOk());
  EXPECT_TRUE(world.addCollider(PlaneCollider{Vec3::UnitX(), -half_width, material}).isOk());
  EXPECT_TRUE(world.addCollider(PlaneCollider{-Vec3::UnitX(), -half_width, material}).isOk());
  EXPECT_TRUE(world.addCollider(PlaneCollider{Vec3::UnitY(), -half_width, material}).isOk());
  EXPECT_TRUE(world.addCollider(PlaneCollider{-Vec3::UnitY(), -half_width, material}).isOk());
  const Real first = -half_width + kRadius;
  for (int layer = 0; layer < layers; ++layer) {
    for (int j = 0; j < side; ++j) {
      for (int i = 0; i < side; ++i) {
        ParticleSpec spec;
        spec.position = Vec3(first + spacing * i, first + spacing * j, kRadius + spacing * layer);
        spec.radius = kRadius;
        EXPECT_TRUE(world.addParticle(spec).isOk());
      }
    }
  }
  return world;
}

class TenLayerPile : public ::testing::TestWithParam<Integrator> {};

// A 10-layer pile (6 x 6 x 10) settles: within 3 s every overlap is below the slop, the kinetic
// energy is that of a speed of 1 mm/s or less, and the pile keeps its height (the lattice neither
// sinks into itself nor is pushed up): the top layer stays within 10 slops below 1.9 m.
// Before resting contacts followed their impulses, every substep sank each sphere by g h^2 = 2.7 mm
// and the position passes left 2-4 mm of overlap in deep piles.
TEST_P(TenLayerPile, SettlesWithOverlapBelowTheSlopAndStaysStill) {
  World world = latticePile(6, 10, GetParam());
  for (int s = 0; s < 180; ++s) world.step();
  const Real slop = world.collisionSettings().penetration_slop;
  const std::size_t n = world.particles().size();
  for (int s = 0; s < 60; ++s) {
    world.step();
    ASSERT_LT(world.lastContactStats().max_penetration, slop) << "step " << s;
    ASSERT_LT(world.kineticEnergy(), 0.5 * n * 1e-6) << "step " << s;  // 1 kg at 1 mm/s each
  }
  const auto z = world.particles().positions().row(2);
  // Each of the 10 contacts under a column may keep up to the slop of overlap.
  const Real top = kRadius + 2.0 * kRadius * 9;
  EXPECT_GT(z.maxCoeff(), top - 10.0 * slop);
  EXPECT_LT(z.maxCoeff(), top + slop);
  EXPECT_GT(z.minCoeff(), kRadius - slop);
  EXPECT_EQ(world.divergenceCount(), 0u);
}

INSTANTIATE_TEST_SUITE_P(EveryIntegrator, TenLayerPile, everyIntegrator(), integratorParamName);

// A settled pile costs few passes: warm-started impulses already hold it, so the velocity phase
// meets its tolerance in at most two passes and the position phase finds nothing to correct (one
// pass). Before, both used all max_iterations (20) every substep.
TEST(ResolverPasses, SettledPileStopsEarly) {
  World world = latticePile(8, 10, Integrator::kSemiImplicitEuler);
  for (int s = 0; s < 180; ++s) world.step();
  for (int s = 0; s < 30; ++s) {
    world.step();
    const ContactStats& stats = world.lastContactStats();
    ASSERT_GT(stats.contacts, 3u * 8 * 8 * 10 - 3u * 8 * 10) << "step " << s;
    EXPECT_LE(stats.velocity_iterations, 2) << "step " << s;
    EXPECT_EQ(stats.position_iterations, 1) << "step " << s;
  }
}

// Friction is warm-started too: a frictional pile (mu 0.5) of spheres dropped at random settles
// and stops creeping. Without the friction warm start each substep rebuilt the friction from zero
// in 20 passes, never quite held the pile, and it kept moving at about 1 cm/s.
TEST(ResolverPasses, FrictionalPileStopsCreeping) {
  WorldConfig config;
  config.gravity = Vec3(0.0, 0.0, -9.81);
  World world(config);
  CollisionSettings settings;
  settings.particle_collisions = true;
  settings.particle_friction = 0.5;
  ASSERT_TRUE(world.setCollisionSettings(settings).isOk());
  const Material material{0.2, 0.5};
  ASSERT_TRUE(world.addCollider(PlaneCollider{Vec3::UnitZ(), 0.0, material}).isOk());
  ASSERT_TRUE(world.addCollider(PlaneCollider{Vec3::UnitX(), -0.3, material}).isOk());
  ASSERT_TRUE(world.addCollider(PlaneCollider{-Vec3::UnitX(), -0.3, material}).isOk());
  ASSERT_TRUE(world.addCollider(PlaneCollider{Vec3::UnitY(), -0.3, material}).isOk());
  ASSERT_TRUE(world.addCollider(PlaneCollider{-Vec3::UnitY(), -0.3, material}).isOk());
  std::mt19937 rng(5);
  std::uniform_real_distribution<Real> jitter(-0.004, 0.004);
  for (int k = 0; k < 8; ++k) {
    for (int j = 0; j < 6; ++j) {
      for (int i = 0; i < 6; ++i) {
        ParticleSpec spec;
        spec.position = Vec3(-0.25 + 0.1 * i + jitter(rng), -0.25 + 0.1 * j + jitter(rng),
                             0.05 + 0.07 * k + jitter(rng));
        spec.radius = 0.03;
        spec.inverse_mass = 10.0;
        ASSERT_TRUE(world.addParticle(spec).isOk());
      }
    }
  }
  for (int s = 0; s < 240; ++s) world.step();
  const Vec3Array before = world.particles().positions();
  Real worst_speed = 0.0;
  for (int s = 0; s < 60; ++s) {
    world.step();
    worst_speed = std::max(worst_speed, world.particles().velocities().colwise().norm().maxCoeff());
  }
  const Real drift = (world.particles().positions() - before).colwise().norm().maxCoeff();
  EXPECT_LT(worst_speed, 1e-3);  // m/s
  EXPECT_LT(drift, 1e-4);        // m over the last second
  EXPECT_LE(world.lastContactStats().velocity_iterations, 2);
}

// Candidate pairs are kept between substeps while no particle moved more than half the skin (a
// quarter of the radius): two spheres far apart when the list is made, approaching slowly (the
// list is kept for about 15 substeps at a time), still meet and bounce off each other, and a third
// one moved onto them by setPosition is pushed out at once.
TEST(CandidatePairs, SlowApproachAndTeleportStillCollide) {
  World world;
  CollisionSettings settings;
  settings.particle_collisions = true;
  settings.particle_restitution = 1.0;
  ASSERT_TRUE(world.setCollisionSettings(settings).isOk());
  ParticleSpec spec;
  spec.radius = kRadius;
  spec.position = Vec3(-0.25, 0.0, 0.0);
  spec.velocity = Vec3(0.05, 0.0, 0.0);
  const ParticleId left = *world.addParticle(spec);
  spec.position = Vec3(0.25, 0.0, 0.0);
  spec.velocity = Vec3(-0.05, 0.0, 0.0);
  const ParticleId right = *world.addParticle(spec);
  spec.position = Vec3(0.0, 5.0, 0.0);
  spec.velocity = Vec3::Zero();
  const ParticleId far = *world.addParticle(spec);
  const Real slop = settings.penetration_slop;
  const auto x = [&](const ParticleId id) {
    return Vec3(world.particles().positions().col(*world.particles().find(id)));
  };
  Real closest = 1.0;
  for (int s = 0; s < 240; ++s) {
    world.step();
    closest = std::min(closest, (x(left) - x(right)).norm());
  }
  EXPECT_GT(closest, 2.0 * kRadius - slop);
  EXPECT_LT(closest, 2.0 * kRadius + slop);  // they did meet
  const auto v = world.particles().velocities();
  EXPECT_NEAR(v(0, *world.particles().find(left)), -0.05, 1e-9);
  EXPECT_NEAR(v(0, *world.particles().find(right)), 0.05, 1e-9);
  // Onto the left one, overlapping it by half a radius.
  ASSERT_TRUE(world.setPosition(far, x(left) + Vec3(0.0, 1.5 * kRadius, 0.0)).isOk());
  world.step();
  EXPECT_GT((x(far) - x(left)).norm(), 2.0 * kRadius - slop);
}

// The candidate pairs are ordered by (height bucket, a, b), whichever broadphase found them, so
// both broadphases give the same contacts in the same order and bit-identical states, also while
// a random pile falls and settles (the list is made again and again).
TEST(CandidatePairs, BothBroadphasesGiveBitIdenticalStates) {
  std::uint64_t hashes[2] = {0, 0};
  for (const Broadphase broadphase : {Broadphase::kSortAndSweep, Broadphase::kUniformGrid}) {
    WorldConfig config;
    config.gravity = Vec3(0.0, 0.0, -9.81);
    World world(config);
    CollisionSettings settings;
    settings.particle_collisions = true;
    settings.broadphase = broadphase;
    settings.particle_friction = 0.3;
    ASSERT_TRUE(world.setCollisionSettings(settings).isOk());
    ASSERT_TRUE(world.addCollider(PlaneCollider{Vec3::UnitZ(), 0.0, Material{0.2, 0.3}}).isOk());
    std::mt19937 rng(9);
    std::uniform_real_distribution<Real> position(-0.4, 0.4);
    std::uniform_real_distribution<Real> radius(0.03, 0.05);
    for (int i = 0; i < 300; ++i) {
      ParticleSpec spec;
      spec.position = Vec3(position(rng), position(rng), 0.5 + std::abs(position(rng)) * 2.0);
      spec.radius = radius(rng);
      ASSERT_TRUE(world.addParticle(spec).isOk());
    }
    for (int s = 0; s < 240; ++s) world.step();
    EXPECT_GT(world.lastContactStats().contacts, 300u);
    hashes[static_cast<int>(broadphase)] = world.stateHash();
  }
  EXPECT_EQ(hashes[0], hashes[1]);
}

// The dense grid (boxes of similar size packed in a compact region) finds exactly the pairs of
// the brute-force test, including boxes exactly one cell apart and boxes touching on a face.
TEST(Broadphase, DenseGridFindsExactlyTheBruteForcePairs) {
  std::mt19937 rng(3);
  BroadphaseFinder finder;
  std::vector<IndexPair> reference;
  std::vector<IndexPair> found;
  for (int scene = 0; scene < 20; ++scene) {
    const int n = 200 + 100 * scene;
    std::uniform_real_distribution<Real> position(-0.1 * std::cbrt(n), 0.1 * std::cbrt(n));
    std::uniform_real_distribution<Real> radius(0.05, 0.09);
    Vec3Array lo(3, n);
    Vec3Array hi(3, n);
    for (int i = 0; i < n; ++i) {
      Vec3 centre(position(rng), position(rng), position(rng));
      // Every fourth box on a lattice of its diameter: exact touching and exact cell distances.
      if (i % 4 == 0) centre = (centre / 0.18).array().round().matrix() * 0.18;
      const Real r = i % 4 == 0 ? 0.09 : radius(rng);
      lo.col(i) = centre - Vec3::Constant(r);
      hi.col(i) = centre + Vec3::Constant(r);
    }
    bruteForcePairs(lo, hi, reference);
    finder.findPairs(Broadphase::kUniformGrid, lo, hi, found);
    std::sort(found.begin(), found.end());
    ASSERT_EQ(found, reference) << "scene " << scene;
  }
}

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
