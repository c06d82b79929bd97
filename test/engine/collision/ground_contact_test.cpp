#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "../integrators/integrator_params.h"
#include "mass_aggregate_sim/engine/world/world.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

constexpr Real kGravity = 9.81;

class BallOnGround : public ::testing::TestWithParam<Integrator> {};

TEST_P(BallOnGround, BouncesToTheRightHeightsThenRests) {
  WorldConfig config;
  config.dt = 1.0 / 60.0;
  config.substeps = 10;
  config.integrator = GetParam();
  config.gravity = Vec3(0.0, 0.0, -kGravity);
  World world(config);
  PlaneCollider ground;
  ground.material.restitution = 0.5;
  ASSERT_TRUE(world.addCollider(ground).isOk());
  const Real radius = 0.1;
  const Real drop = 1.0;
  ParticleSpec spec;
  spec.position = Vec3(0.0, 0.0, radius + drop);
  spec.radius = radius;
  const ParticleId id = *world.addParticle(spec);
  const auto height = [&] { return world.particles().positions()(2, 0) - radius; };
  const auto vz = [&] { return world.particles().velocities()(2, 0); };

  // Apexes of the first two bounces: h_k = e^(2k) h_0 = 0.25 and 0.0625 m. Ten substeps: the
  // contact is found after the substep, up to |v| h inside the ground, which shifts an apex by up
  // to e |v| h (about 4 mm at the first bounce): hence 2 cm and 5 mm tolerances.
  std::vector<Real> apexes;
  Real highest = 0.0;
  bool rising = false;
  for (int s = 0; s < 600 && apexes.size() < 2; ++s) {
    world.step();
    if (vz() > 0.0) {
      rising = true;
      highest = std::max(highest, height());
    } else if (rising) {
      apexes.push_back(highest);
      rising = false;
      highest = 0.0;
    }
  }
  ASSERT_EQ(apexes.size(), 2u);
  EXPECT_NEAR(apexes[0], 0.25 * drop, 0.02 * drop);
  EXPECT_NEAR(apexes[1], 0.0625 * drop, 0.005 * drop);

  // Then it settles and stays: still, and sunk no deeper than the slop.
  for (int s = 0; s < 600; ++s) world.step();
  const Real slop = world.collisionSettings().penetration_slop;
  for (int s = 0; s < 120; ++s) {
    world.step();
    ASSERT_LT(world.particles().velocities().col(0).norm(), 1e-6) << "step " << s;
    ASSERT_LE(-height(), slop) << "step " << s;
    ASSERT_LT(world.lastContactStats().max_penetration, slop);
  }
  EXPECT_GT(height(), -slop);
  (void)id;
}

INSTANTIATE_TEST_SUITE_P(AllIntegrators, BallOnGround, everyIntegrator(), integratorParamName);

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
