// The body solver's row for two particles in contact (particle_pair.h): a pair closing is
// stopped, a gap may close within the substep, friction removes slip within mu times the normal
// impulse (only while the body solver has the contact alone), and the warm start applies the
// kept impulses along the normal now.
#include "engine/bodies/particle_pair.h"

#include <gtest/gtest.h>

#include <vector>

namespace mass_aggregate_sim {
namespace engine {
namespace {

constexpr Real kH = 0.01;

// Two particles of inverse masses 1 and 3 on the x axis, their centres `distance` apart, each
// touching at 0.1; a alone with the body solver.
struct Pair {
  std::vector<SolverBody> bodies = std::vector<SolverBody>(2);
  std::vector<ParticlePair> pairs = std::vector<ParticlePair>(1);

  Pair(const Real distance, const Vec3& v_a, const Vec3& v_b, const Real friction) {
    bodies[0].inverse_mass = 1.0;
    bodies[1].inverse_mass = 3.0;
    bodies[0].v = v_a;
    bodies[1].v = v_b;
    ParticlePair& p = pairs[0];
    p.a = 0;
    p.b = 1;
    p.start_b = Vec3(distance, 0.0, 0.0);
    p.touching = 0.1;
    p.friction = friction;
    p.alone = true;
  }
  const Vec3& va() const { return bodies[0].v; }
  const Vec3& vb() const { return bodies[1].v; }
  Vec3 momentum() const { return va() + vb() / 3.0; }
};

TEST(ParticlePair, TouchingParticlesStopClosingWithMomentumKept) {
  Pair p(0.1, Vec3(2.0, 0.0, 0.0), Vec3(-1.0, 0.0, 0.0), 0.0);
  const Vec3 before = p.momentum();
  solveParticlePairs(p.pairs, p.bodies, kH);
  EXPECT_NEAR(p.vb().x() - p.va().x(), 0.0, 1e-15);
  // j = 3 / (1 + 3) along n = +x, on b; -j on a.
  EXPECT_NEAR(p.pairs[0].normal_impulse, 0.75, 1e-15);
  EXPECT_NEAR((p.momentum() - before).norm(), 0.0, 1e-15);
}

TEST(ParticlePair, SeparatingParticlesArePulledByNothing) {
  Pair p(0.1, Vec3(-1.0, 0.0, 0.0), Vec3(1.0, 0.0, 0.0), 0.5);
  solveParticlePairs(p.pairs, p.bodies, kH);
  EXPECT_EQ(p.pairs[0].normal_impulse, 0.0);
  EXPECT_EQ(p.va(), Vec3(-1.0, 0.0, 0.0));
  EXPECT_EQ(p.vb(), Vec3(1.0, 0.0, 0.0));
}

TEST(ParticlePair, AGapClosesWithinTheSubstepAndNoFaster) {
  // 2 cm apart: closing at 2 m/s closes it in h exactly; at 3 m/s the row takes the extra 1 m/s.
  Pair slow(0.12, Vec3(1.0, 0.0, 0.0), Vec3(-1.0, 0.0, 0.0), 0.0);
  solveParticlePairs(slow.pairs, slow.bodies, kH);
  EXPECT_NEAR(slow.pairs[0].normal_impulse, 0.0, 1e-15);
  Pair fast(0.12, Vec3(2.0, 0.0, 0.0), Vec3(-1.0, 0.0, 0.0), 0.0);
  solveParticlePairs(fast.pairs, fast.bodies, kH);
  EXPECT_NEAR(fast.va().x() - fast.vb().x(), 2.0, 1e-12);
}

TEST(ParticlePair, FrictionStopsSlipInsideTheCone) {
  // Normal impulse 0.75; the slip of 1 m/s along y takes 0.25 (the effective mass), within
  // 0.5 x 0.75.
  Pair p(0.1, Vec3(2.0, 1.0, 0.0), Vec3(-1.0, 0.0, 0.0), 0.5);
  const Vec3 before = p.momentum();
  solveParticlePairs(p.pairs, p.bodies, kH);
  EXPECT_NEAR(p.va().y() - p.vb().y(), 0.0, 1e-15);
  EXPECT_NEAR(p.pairs[0].friction_impulse.y(), -0.25, 1e-15);
  EXPECT_NEAR((p.momentum() - before).norm(), 0.0, 1e-15);
}

TEST(ParticlePair, FrictionSlidesAtMuTimesTheNormalImpulse) {
  // The slip of 4 m/s would take 1.0; Coulomb allows 0.2 x 0.75 = 0.15.
  Pair p(0.1, Vec3(2.0, 4.0, 0.0), Vec3(-1.0, 0.0, 0.0), 0.2);
  solveParticlePairs(p.pairs, p.bodies, kH);
  EXPECT_NEAR(p.pairs[0].friction_impulse.norm(), 0.15, 1e-15);
  EXPECT_NEAR(p.va().y(), 4.0 - 0.15, 1e-15);
  EXPECT_NEAR(p.vb().y(), 3.0 * 0.15, 1e-15);
}

TEST(ParticlePair, APairTheParticleSolverAlsoSolvesOnlyPushes) {
  Pair p(0.1, Vec3(2.0, 4.0, 0.0), Vec3(-1.0, 0.0, 0.0), 0.5);
  p.pairs[0].alone = false;
  solveParticlePairs(p.pairs, p.bodies, kH);
  EXPECT_NEAR(p.pairs[0].normal_impulse, 0.75, 1e-15);
  EXPECT_EQ(p.pairs[0].friction_impulse, Vec3::Zero());
  EXPECT_EQ(p.va().y(), 4.0);
}

TEST(ParticlePair, TheWarmStartAppliesTheKeptImpulsesAlongTheNormalNow) {
  // Kept: 0.5 along the normal, and a friction impulse on a with a part along the normal now
  // (dropped) and one across it beyond the cone (cut to mu j = 0.25).
  Pair p(0.1, Vec3::Zero(), Vec3::Zero(), 0.5);
  p.pairs[0].normal_impulse = 0.5;
  p.pairs[0].friction_impulse = Vec3(0.3, 0.0, 0.4);
  warmStartParticlePairs(p.pairs, p.bodies);
  EXPECT_NEAR(p.pairs[0].friction_impulse.x(), 0.0, 1e-15);
  EXPECT_NEAR(p.pairs[0].friction_impulse.z(), 0.25, 1e-15);
  // On a: f - j n = (-0.5, 0, 0.25); on b its opposite, times 3.
  EXPECT_NEAR((p.va() - Vec3(-0.5, 0.0, 0.25)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((p.vb() - Vec3(1.5, 0.0, -0.75)).norm(), 0.0, 1e-15);
}

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
