// Each force generator against values computed by hand.
#include <gtest/gtest.h>

#include <cmath>

#include "engine/forces/force_stage.h"
#include "mass_aggregate_sim/engine/world/world.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

constexpr Real kTolerance = 1e-12;

class ForceGeneratorTest : public ::testing::Test {
 protected:
  ParticleId add(const Vec3& position, const Vec3& velocity = Vec3::Zero(), Real mass = 2.0) {
    ParticleSpec spec;
    spec.position = position;
    spec.velocity = velocity;
    spec.inverse_mass = 1.0 / mass;
    return particles_.add(spec);
  }
  // The force every generator puts on each particle at the current state.
  Vec3Array forces(const Real gravity_magnitude = 9.81, const Real dt = 0.01) {
    Vec3Array force = Vec3Array::Zero(3, static_cast<Eigen::Index>(particles_.size()));
    ForceStage stage;
    stage.generatorForces(
        ForceScene{particles_, generators_, 0, Vec3(0, 0, -gravity_magnitude), false},
        particles_.positions(), particles_.velocities(), dt, force);
    return force;
  }
  Vec3 forceOn(const ParticleId id, const Real gravity_magnitude = 9.81) {
    return forces(gravity_magnitude).col(static_cast<Eigen::Index>(*particles_.find(id)));
  }

  ParticleStore particles_;
  ForceGenerators generators_;
};

TEST_F(ForceGeneratorTest, DragOpposesVelocityWithLinearAndQuadraticTerms) {
  const ParticleId p = add(Vec3::Zero(), Vec3(3.0, 4.0, 0.0));  // |v| = 5
  generators_.of<Drag>().push_back(Drag{p, 0.5, 0.1});
  // |F| = 0.5 * 5 + 0.1 * 25 = 5, along -v/|v| = (-0.6, -0.8, 0)
  EXPECT_TRUE(forceOn(p).isApprox(Vec3(-3.0, -4.0, 0.0), kTolerance));
}

TEST_F(ForceGeneratorTest, StretchedSpringPullsBothEndsTogether) {
  const ParticleId a = add(Vec3(0.0, 0.0, 0.0));
  const ParticleId b = add(Vec3(3.0, 0.0, 0.0));
  generators_.of<Spring>().push_back(Spring::between(a, b, 10.0, 2.0, 0.0));
  // extension 1 m, k = 10 N/m: 10 N towards each other
  EXPECT_TRUE(forceOn(a).isApprox(Vec3(10.0, 0.0, 0.0), kTolerance));
  EXPECT_TRUE(forceOn(b).isApprox(Vec3(-10.0, 0.0, 0.0), kTolerance));
}

TEST_F(ForceGeneratorTest, CompressedSpringPushesEndsApart) {
  const ParticleId a = add(Vec3(0.0, 0.0, 0.0));
  const ParticleId b = add(Vec3(0.0, 1.5, 0.0));
  generators_.of<Spring>().push_back(Spring::between(a, b, 10.0, 2.0, 0.0));
  // compressed by 0.5 m: 5 N pushing apart (a signed law, not |l - L|)
  EXPECT_TRUE(forceOn(a).isApprox(Vec3(0.0, -5.0, 0.0), kTolerance));
  EXPECT_TRUE(forceOn(b).isApprox(Vec3(0.0, 5.0, 0.0), kTolerance));
}

TEST_F(ForceGeneratorTest, SpringDashpotResistsRelativeVelocityAlongTheSpring) {
  const ParticleId a = add(Vec3(0.0, 0.0, 0.0), Vec3(-1.0, 7.0, 0.0));
  const ParticleId b = add(Vec3(2.0, 0.0, 0.0), Vec3(1.0, 0.0, 0.0));
  generators_.of<Spring>().push_back(Spring::between(a, b, 10.0, 2.0, 3.0));
  // at rest length; ends separate at 2 m/s along the spring (the 7 m/s sideways does not count):
  // dashpot 3 * 2 = 6 N pulling them together
  EXPECT_TRUE(forceOn(a).isApprox(Vec3(6.0, 0.0, 0.0), kTolerance));
  EXPECT_TRUE(forceOn(b).isApprox(Vec3(-6.0, 0.0, 0.0), kTolerance));
}

TEST_F(ForceGeneratorTest, AnchoredSpringPullsTowardsAnchorAndPushesWhenCompressed) {
  const ParticleId far = add(Vec3(0.0, 0.0, 5.0));
  const ParticleId near = add(Vec3(0.0, 0.0, 1.0));
  generators_.of<Spring>().push_back(Spring::anchoredAt(far, Vec3::Zero(), 4.0, 2.0, 0.0));
  generators_.of<Spring>().push_back(Spring::anchoredAt(near, Vec3::Zero(), 4.0, 2.0, 0.0));
  EXPECT_TRUE(forceOn(far).isApprox(Vec3(0.0, 0.0, -12.0), kTolerance));
  EXPECT_TRUE(forceOn(near).isApprox(Vec3(0.0, 0.0, 4.0), kTolerance));
}

TEST_F(ForceGeneratorTest, BungeeIsSlackWhenShortAndPullsWhenStretched) {
  const ParticleId a = add(Vec3(0.0, 0.0, 0.0));
  const ParticleId b = add(Vec3(1.0, 0.0, 0.0));
  const ParticleId c = add(Vec3(0.0, 0.0, 0.0));
  const ParticleId d = add(Vec3(0.0, 4.0, 0.0));
  generators_.of<Spring>().push_back(
      Spring::between(a, b, 10.0, 2.0, 0.0).pullingOnly());  // 1 m < 2 m: slack
  generators_.of<Spring>().push_back(
      Spring::between(c, d, 10.0, 2.0, 0.0).pullingOnly());  // 4 m: 2 m stretch
  const Vec3Array f = forces();
  EXPECT_TRUE(f.col(static_cast<Eigen::Index>(*particles_.find(a))).isZero(0.0));
  EXPECT_TRUE(f.col(static_cast<Eigen::Index>(*particles_.find(b))).isZero(0.0));
  EXPECT_TRUE(forceOn(c).isApprox(Vec3(0.0, 20.0, 0.0), kTolerance));
  EXPECT_TRUE(forceOn(d).isApprox(Vec3(0.0, -20.0, 0.0), kTolerance));
}

TEST_F(ForceGeneratorTest, AnchoredBungeeIsSlackInsideItsRestLength) {
  const ParticleId inside = add(Vec3(1.0, 0.0, 0.0));
  const ParticleId outside = add(Vec3(0.0, -3.0, 0.0));
  generators_.of<Spring>().push_back(
      Spring::anchoredAt(inside, Vec3::Zero(), 5.0, 2.0, 0.0).pullingOnly());
  generators_.of<Spring>().push_back(
      Spring::anchoredAt(outside, Vec3::Zero(), 5.0, 2.0, 0.0).pullingOnly());
  EXPECT_TRUE(forceOn(inside).isZero(0.0));
  EXPECT_TRUE(forceOn(outside).isApprox(Vec3(0.0, 5.0, 0.0), kTolerance));
}

TEST_F(ForceGeneratorTest, BuoyancyIsZeroOutsideFullWhenSubmergedAndLinearBetween) {
  // rho V g = 1000 * 0.002 * 9.81 = 19.62 N when fully submerged
  const Buoyancy params{ParticleId{}, 0.5, 0.002, 1000.0, 1.0, Vec3::UnitZ()};
  const ParticleId above = add(Vec3(0.0, 0.0, 1.6));    // 0.6 above the surface
  const ParticleId deep = add(Vec3(0.0, 0.0, 0.2));     // 0.8 below
  const ParticleId partly = add(Vec3(0.0, 0.0, 1.25));  // 0.25 above: 1/4 submerged
  const ParticleId surface = add(Vec3(0.0, 0.0, 1.0));  // at the surface: half submerged
  for (const ParticleId id : {above, deep, partly, surface}) {
    Buoyancy b = params;
    b.particle = id;
    generators_.of<Buoyancy>().push_back(b);
  }
  const Real full = 1000.0 * 0.002 * 9.81;
  EXPECT_TRUE(forceOn(above).isZero(0.0));
  EXPECT_TRUE(forceOn(deep).isApprox(Vec3(0.0, 0.0, full), kTolerance));
  EXPECT_TRUE(forceOn(partly).isApprox(Vec3(0.0, 0.0, 0.25 * full), kTolerance));
  EXPECT_TRUE(forceOn(surface).isApprox(Vec3(0.0, 0.0, 0.5 * full), kTolerance));
  // always up, and scaled by the world's gravity
  EXPECT_TRUE(forceOn(deep, 1.62).isApprox(Vec3(0.0, 0.0, 1000.0 * 0.002 * 1.62), kTolerance));
}

TEST_F(ForceGeneratorTest, StiffSpringLandsOnTheExactDampedOscillation) {
  // One semi-implicit Euler step with the stiff spring's force lands exactly on the closed form
  // x(t) = e^(-beta t) (x0 cos(g t) + (v0 + beta x0) sin(g t) / g).
  const Real mass = 2.0;
  const Real k = 5000.0;
  const Real c = 20.0;
  const Real dt = 0.05;  // omega dt = 2.5: far beyond what an explicit spring survives
  WorldConfig config;
  config.dt = dt;
  config.integrator = Integrator::kSemiImplicitEuler;
  World world(config);
  ParticleSpec spec;
  spec.position = Vec3(0.3, 0.0, 0.0);
  spec.velocity = Vec3(-1.0, 0.0, 0.0);
  spec.inverse_mass = 1.0 / mass;
  const ParticleId p = *world.addParticle(spec);
  ASSERT_TRUE(world.addGenerator(StiffSpring{p, Vec3::Zero(), k, c}).isOk());
  world.step();
  const Real beta = c / (2.0 * mass);
  const Real g = std::sqrt(k / mass - beta * beta);
  const Real expected =
      std::exp(-beta * dt) * (0.3 * std::cos(g * dt) + (-1.0 + beta * 0.3) * std::sin(g * dt) / g);
  EXPECT_NEAR(world.particles().positions()(0, 0), expected, 1e-12);

  // and it stays bounded and decays over many steps
  for (int i = 0; i < 1000; ++i) world.step();
  EXPECT_LT(world.particles().positions().col(0).norm(), 0.3);
  EXPECT_EQ(world.divergenceCount(), 0u);
}

TEST_F(ForceGeneratorTest, SpringEnergyCountsOnlyStretchedBungees) {
  const ParticleId a = add(Vec3(0.0, 0.0, 0.0));
  const ParticleId b = add(Vec3(3.0, 0.0, 0.0));
  generators_.of<Spring>().push_back(
      Spring::between(a, b, 10.0, 2.0, 0.0));  // 0.5 * 10 * 1^2 = 5 J
  generators_.of<Spring>().push_back(
      Spring::between(a, b, 10.0, 4.0, 0.0).pullingOnly());  // slack: 0 J
  generators_.of<Spring>().push_back(
      Spring::between(a, b, 2.0, 1.0, 0.0).pullingOnly());  // 0.5 * 2 * 2^2 = 4 J
  ForceStage stage;
  EXPECT_NEAR(stage.elasticEnergy(ForceScene{particles_, generators_, 0, Vec3::Zero(), false}), 9.0,
              kTolerance);
}

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
