// A pile made the way users make one (issue 14's 1,000-box random drop, bench/rigid): boxes of
// random sizes at random orientations fall into four walls. Whatever the pile does, contacts
// only take energy out (no restitution here), so the mechanical energy (kinetic plus
// gravitational) of the bodies never rises by more than what pushing out an overlap may add, and
// nothing leaves the walls or the ground. A pseudo-inverse of a manifold's coupled mass kept
// while K had moved a thousandth once threw boxes out at 100 m/s (72 J in one step).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "body_scenes.h"
#include "rigid_scenes.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

using namespace test_bodies;

struct PileRun {
  Real largest_gain = 0.0;  // J, the most one step added to the mechanical energy
  int largest_gain_step = 0;
  int escaped = 0;
  Real final_kinetic = 0.0;
};

PileRun dropTheBoxes(const int substeps, const int steps) {
  const bench::rigid::RigidScene scene = bench::rigid::randomDrop(1000);
  World world(config());
  BodySettings settings;
  settings.substeps = substeps;
  EXPECT_TRUE(world.setBodySettings(settings));
  addGround(world, Material{0.0, scene.ground.friction});
  for (const bench::rigid::BodySpec& b : scene.bodies) {
    BodySpec spec = body(box(b.half_extents, Material{b.restitution, b.friction}),
                         b.isFixed() ? 1.0 : b.mass, b.position, b.orientation);
    if (b.isFixed()) spec.type = BodyType::kFixed;
    EXPECT_TRUE(world.addBody(spec));
  }
  const auto energy = [&]() {
    const BodyStore& bodies = world.bodies();
    Real e = 0.0;
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      if (!bodies.dynamic(i)) continue;
      const Vec3 w = bodies.orientation(i).conjugate() * bodies.angularVelocity(i);
      e += 0.5 * bodies.mass(i) * bodies.linearVelocity(i).squaredNorm() +
           0.5 * w.dot(bodies.principalInertia(i).cwiseProduct(w)) +
           bodies.mass(i) * kG * bodies.position(i).z();
    }
    return e;
  };
  PileRun run;
  Real before = energy();
  for (int step = 1; step <= steps; ++step) {
    world.step();
    const Real now = energy();
    if (now - before > run.largest_gain) {
      run.largest_gain = now - before;
      run.largest_gain_step = step;
    }
    before = now;
  }
  const BodyStore& bodies = world.bodies();
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    if (!bodies.dynamic(i)) continue;
    const Vec3& p = bodies.position(i);
    const bool outside = std::abs(p.x()) > scene.inner_half_width ||
                         std::abs(p.y()) > scene.inner_half_width || p.z() < 0.0;
    run.escaped += outside ? 1 : 0;
  }
  run.final_kinetic = world.kineticEnergy();
  EXPECT_EQ(world.divergenceCount(), 0u);
  return run;
}

TEST(RandomPile, AThousandDroppedBoxesNeverGainEnergyNorLeave) {
  for (const int substeps : {1, 4}) {
    const PileRun run = dropTheBoxes(substeps, 300);
    std::printf(
        "[ pile ] 1,000 random boxes, %d substeps, 5 s: largest energy gain of a step %.2e J "
        "(step %d), %d escaped, kinetic energy %.3e J\n",
        substeps, run.largest_gain, run.largest_gain_step, run.escaped, run.final_kinetic);
    EXPECT_LT(run.largest_gain, 0.05) << substeps << " substeps, step " << run.largest_gain_step;
    EXPECT_EQ(run.escaped, 0) << substeps << " substeps";
  }
}

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
