// Isolated collider contacts are solved four at a time in vector lanes (the collider groups of
// solveColliderGroups, and solveIsolatedBatch); a lone one, or the last one to three of them, in
// scalar code: two instances of the one contact response. Both must give the same bits: balls in
// different states share one world (some in the lanes, the rest in the scalar tail) and each must
// move exactly as in a world of its own, where its contact is the only one and goes the scalar way.
// On a plane without and with friction (the planes are tested in the lanes), and on a large rough
// sphere (tested per particle, solved in the lanes); and the same on the general contact path (a
// contact limit set: contacts are made one by one, then the isolated ones gathered four at a time
// by solveIsolatedBatch, with and without friction).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <vector>

#include "../integrators/integrator_params.h"
#include "mass_aggregate_sim/engine/world/world.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

struct Ball {
  Real bottom = 0.0;  // height of the ball's bottom above the ground (< 0: in it)
  Vec3 velocity = Vec3::Zero();
  Real inverse_mass = 1.0;
  Real radius = 0.1;
  Real x = 0.0;  // where it stands along x, the same in its own world and in the shared one
};

// On a tilted ground plane: resting, dropped, pushed 2 cm in (corrected), falling fast through the
// contact margin (a gap closing faster than it may: inactive), sliding, heavy and small, rising off
// the ground. Apart along x (no particle collisions in this world anyway).
const std::vector<Ball>& balls() {
  static const std::vector<Ball> all = {
      Ball{0.0, Vec3::Zero(), 1.0, 0.1, 0.0},
      Ball{0.3, Vec3::Zero(), 1.0, 0.1, 1.0},
      Ball{-0.02, Vec3::Zero(), 1.0, 0.1, 2.0},
      Ball{0.001, Vec3(0.0, -3.0, 0.0), 1.0, 0.1, 3.0},
      Ball{0.0, Vec3(1.5, 0.0, -0.5), 1.0, 0.1, 4.0},
      Ball{0.0005, Vec3::Zero(), 0.3, 0.05, 5.0},
      Ball{0.0, Vec3(0.0, 0.4, 0.0), 1.0, 0.1, 6.0},
  };
  return all;
}

enum class Ground { kPlane, kRoughPlane, kRoughSphere };
enum class Path { kColliderGroups, kGeneral };

World ballsWorld(const Integrator integrator, const std::vector<Ball>& list, const Ground kind,
                 const Path path) {
  WorldConfig config;
  config.dt = 1.0 / 60.0;
  config.integrator = integrator;
  config.gravity = Vec3(0.0, -9.81, 0.0);
  World world(config);
  if (path == Path::kGeneral) {
    CollisionSettings settings = world.collisionSettings();
    settings.max_contacts = 1000;
    EXPECT_TRUE(world.setCollisionSettings(settings).isOk());
  }
  // Tilted, so every component of the normal takes part in the arithmetic.
  const Vec3 normal = Vec3(0.1, 1.0, 0.05).normalized();
  const Material material{0.4, kind == Ground::kPlane ? 0.0 : 0.5};
  constexpr Real kSphereRadius = 50.0;
  const Vec3 sphere_center = -kSphereRadius * normal;
  if (kind == Ground::kRoughSphere) {
    SphereCollider ground;
    ground.center = sphere_center;
    ground.radius = kSphereRadius;
    ground.material = material;
    EXPECT_TRUE(world.addCollider(ground).isOk());
  } else {
    PlaneCollider ground;
    ground.normal = normal;
    ground.material = material;
    EXPECT_TRUE(world.addCollider(ground).isOk());
  }
  for (std::size_t i = 0; i < list.size(); ++i) {
    ParticleSpec spec;
    const Vec3 along(list[i].x, 0.0, 0.0);
    const Real lift = list[i].radius + list[i].bottom;
    if (kind == Ground::kRoughSphere) {
      const Vec3 out = (along - sphere_center).normalized();
      spec.position = sphere_center + (kSphereRadius + lift) * out;
    } else {
      spec.position = along - normal.dot(along) * normal + lift * normal;
    }
    spec.velocity = list[i].velocity;
    spec.inverse_mass = list[i].inverse_mass;
    spec.radius = list[i].radius;
    spec.damping = 0.99;
    EXPECT_TRUE(world.addParticle(spec).isOk());
  }
  return world;
}

bool sameBits(const Vec3& a, const Vec3& b) { return std::memcmp(a.data(), b.data(), 24) == 0; }

// Steps the shared world and one world per ball side by side: same positions and velocities to
// the bit, same contact count and stats.
void expectEveryBallAsAlone(const Integrator integrator, const std::vector<Ball>& list,
                            const Ground kind, const Path path = Path::kColliderGroups) {
  World together = ballsWorld(integrator, list, kind, path);
  std::vector<World> alone;
  for (const Ball& ball : list) alone.push_back(ballsWorld(integrator, {ball}, kind, path));
  int steps_with_a_batch = 0;
  int corrected_steps = 0;
  for (int s = 0; s < 240; ++s) {
    together.step();
    std::size_t contacts = 0;
    Real max_penetration = 0.0;
    Real max_closing = 0.0;
    for (std::size_t i = 0; i < list.size(); ++i) {
      alone[i].step();
      const Vec3 x_together = together.particles().positions().col(i);
      const Vec3 x_alone = alone[i].particles().positions().col(0);
      ASSERT_TRUE(sameBits(x_together, x_alone))
          << "ball " << i << " step " << s << ": " << x_together.transpose() << " vs "
          << x_alone.transpose();
      ASSERT_TRUE(sameBits(together.particles().velocities().col(i),
                           alone[i].particles().velocities().col(0)))
          << "ball " << i << " step " << s;
      const ContactStats& stats = alone[i].lastContactStats();
      contacts += stats.contacts;
      max_penetration = std::max(max_penetration, stats.max_penetration);
      max_closing = std::max(max_closing, stats.max_closing_velocity);
      if (stats.position_iterations > 1) ++corrected_steps;
    }
    const ContactStats& stats = together.lastContactStats();
    ASSERT_EQ(stats.contacts, contacts) << "step " << s;
    ASSERT_EQ(stats.max_penetration, max_penetration) << "step " << s;
    ASSERT_EQ(stats.max_closing_velocity, max_closing) << "step " << s;
    if (stats.contacts >= 4) ++steps_with_a_batch;
  }
  EXPECT_GT(steps_with_a_batch, 100);
  EXPECT_GT(corrected_steps, 0);
  EXPECT_EQ(together.divergenceCount(), 0u);
}

class IsolatedContactBatch : public ::testing::TestWithParam<Integrator> {};

TEST_P(IsolatedContactBatch, EveryBallMovesAsAlone) {
  expectEveryBallAsAlone(GetParam(), balls(), Ground::kPlane);
}

// Reversed, the balls that were in the scalar tail are in the lanes and the other way round.
TEST_P(IsolatedContactBatch, EveryBallMovesAsAloneInTheOtherOrder) {
  std::vector<Ball> reversed = balls();
  std::reverse(reversed.begin(), reversed.end());
  expectEveryBallAsAlone(GetParam(), reversed, Ground::kPlane);
}

TEST_P(IsolatedContactBatch, EveryBallMovesAsAloneOnARoughPlane) {
  expectEveryBallAsAlone(GetParam(), balls(), Ground::kRoughPlane);
}

TEST_P(IsolatedContactBatch, EveryBallMovesAsAloneOnARoughSphere) {
  expectEveryBallAsAlone(GetParam(), balls(), Ground::kRoughSphere);
}

TEST_P(IsolatedContactBatch, EveryBallMovesAsAloneOnTheGeneralPath) {
  expectEveryBallAsAlone(GetParam(), balls(), Ground::kPlane, Path::kGeneral);
}

TEST_P(IsolatedContactBatch, EveryBallMovesAsAloneOnARoughPlaneOnTheGeneralPath) {
  expectEveryBallAsAlone(GetParam(), balls(), Ground::kRoughPlane, Path::kGeneral);
}

TEST_P(IsolatedContactBatch, EveryBallMovesAsAloneOnARoughSphereOnTheGeneralPath) {
  expectEveryBallAsAlone(GetParam(), balls(), Ground::kRoughSphere, Path::kGeneral);
}

// Reversed on the rough plane: the friction contacts that were in the scalar tail go in the lanes.
TEST_P(IsolatedContactBatch, EveryBallMovesAsAloneOnARoughPlaneOnTheGeneralPathInTheOtherOrder) {
  std::vector<Ball> reversed = balls();
  std::reverse(reversed.begin(), reversed.end());
  expectEveryBallAsAlone(GetParam(), reversed, Ground::kRoughPlane, Path::kGeneral);
}

INSTANTIATE_TEST_SUITE_P(AllIntegrators, IsolatedContactBatch, everyIntegrator(),
                         integratorParamName);

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
