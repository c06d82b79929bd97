// Bodies on the ground (issue 14's acceptance tests 4-7): a cube at rest, a cube dropped flat
// that bounces, a Coulomb slide, inclines that hold, slide and roll. Analytic answers.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "body_scenes.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

using namespace test_bodies;

// The sum of the contacts' normal impulses on body id over the last substep, as a force (the
// report's impulses are over a substep of the last step, asleep or not).
Real normalForce(const World& world, const BodyId id) {
  Real impulse = 0.0;
  for (const BodyContactReport& c : world.bodyContacts()) {
    if (c.body != id) continue;
    for (const auto& p : c.points) impulse += p.normal_impulse;
  }
  return impulse / (world.config().dt / world.substepsUsed());
}

TEST(BodyContact, ACubeRestsOnThePlane) {
  World world(config());
  addGround(world);
  const Real m = 3.0;
  const BodyId id = *world.addBody(body(box(Vec3::Constant(0.5)), m, Vec3(0.0, 0.0, 0.5)));
  const std::size_t i = *world.bodies().find(id);
  Real force_sum = 0.0;
  int force_steps = 0;
  Real worst_overlap = 0.0;
  for (int step = 0; step < 600; ++step) {
    world.step();
    if (step >= 60) {
      force_sum += normalForce(world, id);
      ++force_steps;
    }
    worst_overlap = std::max(worst_overlap, maxOverlap(world));
  }
  const Vec3 drift = world.bodies().position(i) - Vec3(0.0, 0.0, 0.5);
  std::printf("[ rest ] drift %.2e m, overlap %.2e m, |w| %.2e, KE %.2e J, mean force / mg %.6f\n",
              drift.norm(), worst_overlap, world.bodies().angularVelocity(i).norm(),
              world.kineticEnergy(), force_sum / force_steps / (m * kG));
  EXPECT_LT(drift.norm(), 1e-3);
  EXPECT_LT(worst_overlap, world.bodySettings().linear_slop);
  EXPECT_LT(world.bodies().angularVelocity(i).norm(), 1e-3);
  EXPECT_LT(world.kineticEnergy(), 1e-6);
  EXPECT_NEAR(force_sum / force_steps, m * kG, 0.01 * m * kG);
}

TEST(BodyContact, ACubeDroppedFlatBouncesToTheQuarterHeight) {
  World world(config());
  addGround(world, Material{0.5, 0.5});
  const BodyId id =
      *world.addBody(body(box(Vec3::Constant(0.5), Material{0.5, 0.5}), 1.0, Vec3(0.0, 0.0, 1.5)));
  const std::size_t i = *world.bodies().find(id);
  Real rebound = 0.0;
  Real apex = 0.0;
  Real worst_w = 0.0;
  bool bounced = false;
  bool falling_again = false;
  for (int step = 0; step < 600; ++step) {
    world.step();
    const Vec3& v = world.bodies().linearVelocity(i);
    worst_w = std::max(worst_w, world.bodies().angularVelocity(i).norm());
    if (!bounced && v.z() > 0.0) {
      // The speed it left the ground with: in flight, v^2 + 2 g (z - 0.5) stays what it was.
      bounced = true;
      rebound = std::sqrt(v.z() * v.z() + 2.0 * kG * (world.bodies().position(i).z() - 0.5));
    }
    if (bounced && !falling_again) {
      apex = std::max(apex, world.bodies().position(i).z() - 0.5);
      if (v.z() < 0.0) falling_again = true;
    }
  }
  // sqrt(2 g 1 m) = 4.429 m/s in, e = 0.5: 2.215 m/s out, apex 2.215^2 / 2g = 0.25 m.
  std::printf("[ bounce ] rebound %.4f m/s, apex %.4f m, |w| %.2e, final KE %.2e J\n", rebound,
              apex, worst_w, world.kineticEnergy());
  EXPECT_NEAR(rebound, 2.215, 0.02 * 2.215);
  EXPECT_NEAR(apex, 0.25, 0.02 * 0.25);
  EXPECT_LT(worst_w, 1e-3);
  EXPECT_LT(world.bodies().linearVelocity(i).norm(), world.bodySettings().restitution_threshold);
  EXPECT_LT(world.kineticEnergy(), 1e-6);
}

// A 1 kg unit cube resting on the ground (mu 0.5 both) with velocities v and w; its dense index.
std::size_t cubeOnTheGround(World& world, const Vec3& v, const Vec3& w) {
  addGround(world, Material{0.0, 0.5});
  BodySpec spec = body(box(Vec3::Constant(0.5), Material{0.0, 0.5}), 1.0, Vec3(0.0, 0.0, 0.5));
  spec.linear_velocity = v;
  spec.angular_velocity = w;
  return *world.bodies().find(*world.addBody(spec));
}

TEST(BodyContact, ACoulombSlideStopsWhereFrictionSays) {
  World world(config());
  const std::size_t i = cubeOnTheGround(world, Vec3(5.0, 0.0, 0.0), Vec3::Zero());
  Real stop_time = -1.0;
  Real worst_w = 0.0;
  for (int step = 1; step <= 120; ++step) {
    world.step();
    worst_w = std::max(worst_w, world.bodies().angularVelocity(i).norm());
    // Stopped: below 1 % of the speed it started with (static friction then holds it).
    if (stop_time < 0.0 && world.bodies().linearVelocity(i).x() < 0.05) stop_time = step / 60.0;
  }
  // v^2 / (2 mu g) = 2.548 m after v / (mu g) = 1.019 s.
  const Real distance = world.bodies().position(i).x();
  std::printf("[ slide ] %.4f m in %.4f s, |w| at most %.2e\n", distance, stop_time, worst_w);
  EXPECT_NEAR(distance, 2.548, 0.02 * 2.548);
  EXPECT_NEAR(stop_time, 1.019, 0.02 * 1.019);
  EXPECT_LT(worst_w, 0.05);  // no tumbling
}

// Friction acts on a contact as a whole: a force at its points' centre and a twist about its
// normal bounded by mu sum j_k d_k (d_k a point's distance from the centre). A unit cube of 1 kg
// spinning on its face at w0 = 5 rad/s (mu 0.5) rests on its four corners, d = 1/sqrt(2): the
// torque mu m g / sqrt(2) against I_z = m / 6 slows it at 6 mu g / sqrt(2) = 20.81 rad/s^2, so it
// stops after w0 / 20.81 = 0.2403 s having turned w0^2 / (2 * 20.81) = 0.6007 rad, less w0 h / 2
// = 0.0104 rad (semi-implicit Euler turns by the speed after each substep's slowing): 0.5903 rad,
// and does not move off its spot. Without the twist row nothing would stop it.
TEST(BodyContact, ASpinningCubeStopsWhereItsCornersFrictionSays) {
  World world(config());
  const std::size_t i = cubeOnTheGround(world, Vec3::Zero(), Vec3(0.0, 0.0, 5.0));
  const Real h = world.config().dt / world.bodySettings().substeps;
  Real stop_time = -1.0;
  Real angle = 0.0;
  Real worst_torque_error = 0.0;
  Real worst_force_sum = 0.0;
  for (int step = 1; step <= 60; ++step) {
    const Real before = world.bodies().angularVelocity(i).z();
    world.step();
    const Quat q = world.bodies().orientation(i);
    angle = 2.0 * std::atan2(q.z(), q.w());
    if (stop_time < 0.0 && world.bodies().angularVelocity(i).z() < 0.05) stop_time = step / 60.0;
    // While it spins, the report's points carry the twist: no net force, and the torque about
    // the centre mu (sum of normal impulses) d, against the turn (the report's friction is what
    // the cube gives the ground: the cube takes the opposite).
    if (before > 0.5) {
      for (const BodyContactReport& c : world.bodyContacts()) {
        Vec3 center = Vec3::Zero();
        for (const auto& p : c.points) center += p.position;
        center /= static_cast<Real>(c.points.size());
        Vec3 force = Vec3::Zero();
        Real torque = 0.0;
        Real load = 0.0;
        for (const auto& p : c.points) {
          force += p.friction_impulse;
          torque -= (p.position - center).cross(p.friction_impulse).z();
          load += p.normal_impulse;
        }
        worst_force_sum = std::max(worst_force_sum, force.norm());
        worst_torque_error =
            std::max(worst_torque_error, std::abs(torque + 0.5 * load * std::sqrt(0.5)) / (kG * h));
      }
    }
  }
  const Vec3 moved = world.bodies().position(i) - Vec3(0.0, 0.0, 0.5);
  std::printf(
      "[ spin ] stopped after %.4f s, turned %.4f rad, moved %.2e m; report: net force %.1e N s, "
      "torque off by %.1e of m g h\n",
      stop_time, angle, moved.norm(), worst_force_sum, worst_torque_error);
  EXPECT_NEAR(stop_time, 0.2403, 1.0 / 60.0);  // judged at whole steps
  EXPECT_NEAR(angle, 0.5903, 0.005 * 0.5903);
  EXPECT_LT(moved.norm(), 1e-6);
  EXPECT_LT(worst_force_sum, 1e-12);
  EXPECT_LT(worst_torque_error, 1e-9);
}

// A sphere touches the ground at one point, which has no lever against turning about the normal:
// only BodySettings::min_twist_lever resists that spin.
TEST(BodyContact, ASphereSpinningOnTheGroundSlowsByTheLeastTwistLever) {
  const auto spin = [](const Real lever) {
    World world(config());
    BodySettings settings = world.bodySettings();
    settings.sleep = false;
    settings.min_twist_lever = lever;
    EXPECT_TRUE(world.setBodySettings(settings));
    addGround(world, Material{0.0, 0.5});
    const Real r = 0.25;
    BodySpec spec = body(sphere(r, Material{0.0, 0.5}), 1.0, Vec3(0.0, 0.0, r));
    spec.angular_velocity = Vec3(0.0, 0.0, 1.0);
    const std::size_t i = *world.bodies().find(*world.addBody(spec));
    for (int step = 0; step < 60; ++step) world.step();
    const Vec3 moved = world.bodies().position(i) - Vec3(0.0, 0.0, r);
    EXPECT_LT(moved.norm(), 1e-9);
    return world.bodies().angularVelocity(i);
  };
  // tau = mu m g d and I = 2/5 m r^2: w' = -mu g d / (2/5 r^2) = -0.19620 rad/s^2 for d = 1 mm,
  // so after 1 s w = 1 - 0.19620 = 0.80380 rad/s about z.
  EXPECT_EQ(BodySettings{}.min_twist_lever, 0.001);
  const Vec3 slowed = spin(0.001);
  const Vec3 kept = spin(0.0);
  std::printf("[ twist ] w after 1 s: %.5f rad/s with a 1 mm lever, %.5f with none\n", slowed.z(),
              kept.z());
  EXPECT_NEAR(slowed.z(), 1.0 - 0.5 * kG * 0.001 / (0.4 * 0.25 * 0.25), 1e-3);
  EXPECT_LT(slowed.head<2>().norm(), 1e-9);
  EXPECT_NEAR(kept.z(), 1.0, 1e-12);
}

TEST(BodyContact, ATallBoxLeftOnOneEdgeRocksBackAndSettlesOnItsBase) {
  // 24.5 x 21 x 55.2 cm, 27 g, tilted 2 degrees about y onto one bottom edge (the other 8.5 mm up):
  // gravity turns it back onto its base, and with restitution 0 each landing can only take
  // energy away. Its centre starts at h cos 2 + b sin 2 above the ground (h, b its half extents
  // up and across the turn) and may never rise above that.
  World world(config());
  BodySettings settings = world.bodySettings();
  settings.sleep = false;
  ASSERT_TRUE(world.setBodySettings(settings));
  addGround(world, Material{0.0, 0.5});
  const Vec3 half(0.1225, 0.105, 0.276);
  const Real tilt = 2.0 * M_PI / 180.0;
  const Real start = half.z() * std::cos(tilt) + half.x() * std::sin(tilt);
  const Quat q(Eigen::AngleAxis<Real>(tilt, Vec3::UnitY()));
  const BodyId id =
      *world.addBody(body(box(half, Material{0.0, 0.5}), 0.027, Vec3(0.0, 0.0, start), q));
  const std::size_t i = *world.bodies().find(id);
  Real highest = 0.0;
  for (int step = 0; step < 600; ++step) {
    world.step();
    highest = std::max(highest, world.bodies().position(i).z());
  }
  std::printf("[ rock ] centre at most %.5f m (started at %.5f), at 10 s %.5f m, KE %.1e J\n",
              highest, start, world.bodies().position(i).z(), world.kineticEnergy());
  EXPECT_LE(highest, start + 1e-4);
  EXPECT_NEAR(world.bodies().position(i).z(), half.z(), 1e-3);  // on its base, not its side
  EXPECT_LT(world.kineticEnergy(), 1e-9);
}

// The cube on the ground sliding from v0 along `direction` (in the plane):
// where it ends up along and across that direction, and when it stopped.
struct ObliqueSlide {
  Real along = 0.0;
  Real across = 0.0;
  Real stop_time = -1.0;
  Real worst_w = 0.0;
};

ObliqueSlide slideAlong(const Vec3& direction, const Real v0) {
  World world(config());
  const Vec3 u = direction.normalized();
  const std::size_t i = cubeOnTheGround(world, v0 * u, Vec3::Zero());
  ObliqueSlide slide;
  for (int step = 1; step <= 120; ++step) {
    world.step();
    slide.worst_w = std::max(slide.worst_w, world.bodies().angularVelocity(i).norm());
    if (slide.stop_time < 0.0 && world.bodies().linearVelocity(i).norm() < 0.01 * v0) {
      slide.stop_time = step / 60.0;
    }
  }
  Vec3 moved = world.bodies().position(i) - Vec3(0.0, 0.0, 0.5);
  moved.z() = 0.0;
  slide.along = moved.dot(u);
  slide.across = (moved - slide.along * u).norm();
  return slide;
}

TEST(BodyContact, AnObliqueSlideStopsWhereCoulombSaysWithoutDrift) {
  // The ground's friction rows lie along its tangents t0 = y, t1 = -x. Coulomb's friction is
  // mu m g against the velocity whatever its direction (the cone |f| <= mu N): the cube slides
  // straight along its first direction and stops after v0^2 / (2 mu g) = 2.548 m and
  // v0 / (mu g) = 1.019 s, as along x. Each row clamped alone to +-mu N (a box) would pull with
  // mu N on both axes once both slide: along (1, 1) sqrt(2) mu m g, stopping after
  // 2.548 / sqrt(2) = 1.80 m; along (3, 1) the y part stops first (after 0.32 s) and the path
  // bends, ending 0.48 m to the side. So: 2 % along as for the slide along x, < 1 cm across.
  // (Checked with the solver's rows clamped as a box: 1.79 m along (1, 1), 0.48 m across (3, 1).)
  const Real v0 = 5.0;
  const Real distance = v0 * v0 / (2.0 * 0.5 * kG);
  const Real time = v0 / (0.5 * kG);
  for (const Vec3& direction : {Vec3(1.0, 1.0, 0.0), Vec3(3.0, 1.0, 0.0), Vec3(-1.0, 2.0, 0.0)}) {
    const ObliqueSlide slide = slideAlong(direction, v0);
    std::printf(
        "[ slide ] along (%g, %g): %.4f m along (exact %.4f), %.2e m across, stopped at "
        "%.4f s (exact %.4f), |w| at most %.2e\n",
        direction.x(), direction.y(), slide.along, distance, slide.across, slide.stop_time, time,
        slide.worst_w);
    EXPECT_NEAR(slide.along, distance, 0.02 * distance) << direction.transpose();
    EXPECT_LT(slide.across, 0.01) << direction.transpose();
    EXPECT_NEAR(slide.stop_time, time, 0.02 * time) << direction.transpose();
    EXPECT_LT(slide.worst_w, 0.05) << direction.transpose();  // no tumbling
  }
}

// A ball (r 0.25 m, 1 kg, frictionless, restitution e on both sides: the pair's is their mean, e)
// 5 cm above the ground coming down at `speed` without gravity: its vertical velocity 0.5 s
// later, long after the impact.
Real reboundVelocity(const Real speed, const Real e, const Real threshold) {
  World world(config(0.0));
  BodySettings settings;
  settings.restitution_threshold = threshold;
  EXPECT_TRUE(world.setBodySettings(settings));
  addGround(world, Material{e, 0.0});
  BodySpec ball = body(sphere(0.25, Material{e, 0.0}), 1.0, Vec3(0.0, 0.0, 0.3));
  ball.linear_velocity = Vec3(0.0, 0.0, -speed);
  const BodyId id = *world.addBody(ball);
  for (int step = 0; step < 30; ++step) world.step();
  return world.bodies().linearVelocity(*world.bodies().find(id)).z();
}

TEST(BodyContact, RestitutionActsOnlyAboveTheThreshold) {
  // A closing speed above BodySettings::restitution_threshold (1 m/s by default) bounces back at
  // e v; at or below it the contact only stops the body (v = 0: it stays on the ground). With e
  // = 1: 0.8 m/s in gives 0 out, 2 m/s in gives 2 m/s out; with e = 0.5, 2 m/s gives 1 m/s. The
  // threshold is the setting: lowered to 0.5 m/s the 0.8 m/s ball bounces, raised to 3 m/s the
  // 2 m/s one does not.
  EXPECT_EQ(BodySettings{}.restitution_threshold, 1.0);
  const Real slow = reboundVelocity(0.8, 1.0, 1.0);
  const Real fast = reboundVelocity(2.0, 1.0, 1.0);
  const Real half = reboundVelocity(2.0, 0.5, 1.0);
  const Real slow_low_threshold = reboundVelocity(0.8, 1.0, 0.5);
  const Real fast_high_threshold = reboundVelocity(2.0, 1.0, 3.0);
  std::printf(
      "[ threshold ] e 1: 0.8 m/s in, %.2e m/s out; 2 m/s in, %.6f m/s out; e 0.5: 2 m/s "
      "in, %.6f m/s out; threshold 0.5: %.6f; threshold 3: %.2e\n",
      slow, fast, half, slow_low_threshold, fast_high_threshold);
  EXPECT_NEAR(slow, 0.0, 1e-6);
  EXPECT_NEAR(fast, 2.0, 1e-6 * 2.0);
  EXPECT_NEAR(half, 1.0, 1e-6 * 1.0);
  EXPECT_NEAR(slow_low_threshold, 0.8, 1e-6 * 0.8);
  EXPECT_NEAR(fast_high_threshold, 0.0, 1e-6);
}

// The plane tilted by `degrees` about y, rising along -x (down the slope is +x).
Vec3 inclineNormal(const Real degrees) {
  const Real a = degrees * M_PI / 180.0;
  return Vec3(std::sin(a), 0.0, std::cos(a));
}

// Down the slope: gravity's part along the plane, g sin a (cos a, 0, -sin a).
Vec3 downSlope(const Real degrees) {
  const Real a = degrees * M_PI / 180.0;
  return Vec3(std::cos(a), 0.0, -std::sin(a));
}

// A body resting on the incline at the origin, its centre `height` above the plane.
Vec3 onIncline(const Real degrees, const Real height) { return height * inclineNormal(degrees); }

TEST(BodyContact, ABoxHoldsOnAGentleIncline) {
  World world(config());
  addGround(world, Material{0.0, 0.5}, inclineNormal(20.0));
  const Quat tilt(Eigen::AngleAxisd(20.0 * M_PI / 180.0, Vec3::UnitY()));
  const BodyId id = *world.addBody(
      body(box(Vec3::Constant(0.5), Material{0.0, 0.5}), 1.0, onIncline(20.0, 0.5), tilt));
  const std::size_t i = *world.bodies().find(id);
  const Vec3 start = world.bodies().position(i);
  for (int step = 0; step < 300; ++step) world.step();
  const Real creep = (world.bodies().position(i) - start).norm();
  std::printf("[ incline ] box at 20 deg, mu 0.5: crept %.2e m in 5 s\n", creep);
  EXPECT_LT(creep, 1e-3);
}

TEST(BodyContact, ABoxSlidesDownASteepSlipperyIncline) {
  World world(config());
  addGround(world, Material{0.0, 0.1}, inclineNormal(30.0));
  const Quat tilt(Eigen::AngleAxisd(30.0 * M_PI / 180.0, Vec3::UnitY()));
  const BodyId id = *world.addBody(
      body(box(Vec3::Constant(0.5), Material{0.0, 0.1}), 1.0, onIncline(30.0, 0.5), tilt));
  const std::size_t i = *world.bodies().find(id);
  for (int step = 0; step < 30; ++step) world.step();  // settle onto the slope
  const Vec3 down_slope = downSlope(30.0);
  const Real v0 = world.bodies().linearVelocity(i).dot(down_slope);
  for (int step = 0; step < 60; ++step) world.step();
  const Real a = (world.bodies().linearVelocity(i).dot(down_slope) - v0) / 1.0;
  // g (sin 30 - 0.1 cos 30) = 9.81 (0.5 - 0.0866) = 4.0554 m/s^2, to 1 %.
  const Real exact = kG * (0.5 - 0.1 * std::cos(M_PI / 6.0));
  std::printf("[ incline ] box at 30 deg, mu 0.1: a = %.4f m/s^2 (exact %.4f)\n", a, exact);
  EXPECT_NEAR(exact, 4.055, 1e-3);
  EXPECT_NEAR(a, exact, 0.01 * exact);
}

TEST(BodyContact, ASphereRollsDownAnIncline) {
  World world(config());
  addGround(world, Material{0.0, 0.5}, inclineNormal(30.0));
  const Real r = 0.25;
  const BodyId id = *world.addBody(body(sphere(r, Material{0.0, 0.5}), 1.0, onIncline(30.0, r)));
  const std::size_t i = *world.bodies().find(id);
  const Vec3 start = world.bodies().position(i);
  for (int step = 0; step < 60; ++step) world.step();
  const Vec3 down_slope = downSlope(30.0);
  // Rolling without slipping, m a = m g sin 30 - f and I w' = f r with w = v / r,
  // I = 2/5 m r^2: a = g sin 30 / (1 + 2/5) = 5/7 g sin 30 = 3.504 m/s^2, so after t = 1 s
  // v = a t = 3.504 m/s down the slope and s = a t^2 / 2 = 1.752 m, rolling (w = v / r).
  const Real a = 5.0 / 7.0 * kG * 0.5;
  const Real t = 1.0;
  const Real distance = (world.bodies().position(i) - start).dot(down_slope);
  const Real v = world.bodies().linearVelocity(i).norm();
  const Real v_down = world.bodies().linearVelocity(i).dot(down_slope);
  const Real w = world.bodies().angularVelocity(i).norm();
  std::printf("[ roll ] %.4f m after 1 s, v %.4f m/s (exact %.4f), w r %.4f m/s\n", distance, v,
              a * t, w * r);
  EXPECT_NEAR(distance, 1.752, 0.01 * 1.752);
  EXPECT_NEAR(v_down, a * t, 0.01 * a * t);
  EXPECT_NEAR(v, v_down, 1e-3 * v);  // along the slope, not off it
  EXPECT_NEAR(w * r, v, 0.01 * v);
}

TEST(BodyContact, ADivergedBodyLeavesTheBroadphaseAndComesBack) {
  // A kinematic box spun at -1e305 rad/s turns non-finite; under kContinue the world steps on
  // (this aborted in DynamicTree::moveProxy on a NaN box: fuzz regression
  // engine-body-diverged-broadphase-assert). The other box keeps resting on its neighbour, and
  // the diverged box, given a finite pose again, meets the ground again.
  World world(config());
  addGround(world);
  BodySpec spun = body(box(Vec3::Constant(0.5)), 1.0, Vec3(0.0, 0.0, 0.5));
  spun.type = BodyType::kKinematic;
  const BodyId wild = *world.addBody(spun);
  const BodyId rest = *world.addBody(body(box(Vec3::Constant(0.5)), 1.0, Vec3(3.0, 0.0, 0.5)));
  ASSERT_TRUE(world.addBody(body(box(Vec3::Constant(0.5)), 1.0, Vec3(3.0, 0.0, 1.5))));
  ASSERT_TRUE(world.setBodyVelocity(wild, Vec3::Zero(), Vec3(0.0, 0.0, -1e305)));
  for (int step = 0; step < 5; ++step) world.step();
  EXPECT_GT(world.divergenceCount(), 0u);
  const auto touching = [&](const BodyId id) {
    int n = 0;
    for (const BodyContactReport& c : world.bodyContacts()) {
      n += (c.body == id || c.other_body == id) && !c.points.empty() ? 1 : 0;
    }
    return n;
  };
  EXPECT_EQ(touching(rest), 2);  // the ground and the box on it
  ASSERT_TRUE(world.setBodyPose(wild, Transform{Vec3(0.0, 0.0, 0.6), Quat::Identity()}));
  ASSERT_TRUE(world.setBodyVelocity(wild, Vec3::Zero(), Vec3::Zero()));
  for (int step = 0; step < 3; ++step) world.step();
  EXPECT_TRUE(world.bodies().pose(*world.bodies().find(wild)).position.allFinite());
  EXPECT_EQ(touching(wild), 0);  // kinematic against the ground: no contact kept
  ASSERT_TRUE(world.addBody(body(box(Vec3::Constant(0.5)), 1.0, Vec3(0.0, 0.0, 1.7))));
  for (int step = 0; step < 30; ++step) world.step();
  EXPECT_EQ(touching(wild), 1);  // the box dropped on it lands on it
}

// The ground, and bodies that never sleep (a body at rest keeps being stepped).
World groundWithoutSleep() {
  World world(config());
  BodySettings settings;
  settings.sleep = false;
  EXPECT_TRUE(world.setBodySettings(settings));
  addGround(world);
  return world;
}

// The broadphase keeps its pairs from step to step and looks again only around the boxes that
// changed: a collider added beside a body that has stopped moving must still be met, and one
// removed must let go.
TEST(BodyContact, AColliderAddedBesideARestingBodyIsMetAndRemovedLetsGo) {
  World world = groundWithoutSleep();
  const BodyId id = *world.addBody(body(box(Vec3::Constant(0.5)), 1.0, Vec3(0.0, 0.0, 0.5)));
  for (int step = 0; step < 60; ++step) world.step();
  const auto touchesCollider = [&](const ColliderId collider) {
    for (const BodyContactReport& c : world.bodyContacts()) {
      if (c.body == id && c.other == BodyContactReport::Other::kCollider &&
          c.collider == collider && !c.points.empty()) {
        return true;
      }
    }
    return false;
  };
  BoxCollider wall;
  wall.center = Vec3(0.6, 0.0, 0.5);  // its face 5 mm from the box's side
  wall.half_extents = Vec3(0.095, 1.0, 1.0);
  const ColliderId wall_id = *world.addCollider(wall);
  world.step();
  EXPECT_TRUE(touchesCollider(wall_id));
  ASSERT_TRUE(world.removeCollider(wall_id));
  world.step();
  EXPECT_FALSE(touchesCollider(wall_id));
  EXPECT_EQ(world.bodyContacts().size(), 1u);  // the ground
}

// A fixed body set somewhere else (a platform or an obstacle moved by a request) is met where
// it is now: a box dropped onto it lands on it, and nothing rests on where it was.
TEST(BodyContact, AFixedBodySetElsewhereIsMetWhereItIsNow) {
  World world = groundWithoutSleep();
  BodySpec platform = body(box(Vec3(1.0, 1.0, 0.1)), 1.0, Vec3(0.0, 0.0, 1.0));
  platform.type = BodyType::kFixed;
  const BodyId platform_id = *world.addBody(platform);
  for (int step = 0; step < 5; ++step) world.step();
  ASSERT_TRUE(world.setBodyPose(platform_id, Transform{Vec3(5.0, 0.0, 1.0), Quat::Identity()}));
  const BodyId dropped = *world.addBody(body(box(Vec3::Constant(0.25)), 1.0, Vec3(5.0, 0.0, 1.6)));
  const BodyId below_old =
      *world.addBody(body(box(Vec3::Constant(0.25)), 1.0, Vec3(0.0, 0.0, 1.6)));
  for (int step = 0; step < 120; ++step) world.step();
  const auto height = [&](const BodyId id) {
    return world.bodies().pose(*world.bodies().find(id)).position.z();
  };
  EXPECT_NEAR(height(dropped), 1.35, 0.01);    // on the platform: 1.0 + 0.1 + 0.25
  EXPECT_NEAR(height(below_old), 0.25, 0.01);  // on the ground, through where it was
}

// Bodies removed and added in their places (the tree reuses the removed proxies' ids, the store
// their shapes): every box of a row on the ground touches the ground and its neighbours, and no
// contact holds a removed body.
TEST(BodyContact, BodiesAddedWhereOthersWereRemovedMeetTheirNeighbours) {
  World world = groundWithoutSleep();
  constexpr int kBoxes = 12;
  std::vector<BodyId> row;
  for (int k = 0; k < kBoxes; ++k) {
    row.push_back(*world.addBody(body(box(Vec3::Constant(0.5)), 1.0, Vec3(k, 0.0, 0.5))));
  }
  for (int step = 0; step < 30; ++step) world.step();
  std::vector<BodyId> removed;
  for (int k = 1; k < kBoxes; k += 3) {
    ASSERT_TRUE(world.removeBody(row[static_cast<std::size_t>(k)]));
    removed.push_back(row[static_cast<std::size_t>(k)]);
  }
  world.step();
  for (int k = 1; k < kBoxes; k += 3) {
    row[static_cast<std::size_t>(k)] =
        *world.addBody(body(box(Vec3::Constant(0.5)), 1.0, Vec3(k, 0.0, 0.5)));
  }
  for (int step = 0; step < 3; ++step) world.step();
  std::vector<int> touching(kBoxes, 0);
  for (const BodyContactReport& c : world.bodyContacts()) {
    for (const BodyId gone : removed) {
      EXPECT_NE(c.body, gone);
      EXPECT_NE(c.other_body, gone);
    }
    if (c.points.empty()) continue;
    for (int k = 0; k < kBoxes; ++k) {
      const BodyId id = row[static_cast<std::size_t>(k)];
      touching[static_cast<std::size_t>(k)] +=
          (c.body == id ? 1 : 0) + (c.other_body == id ? 1 : 0);
    }
  }
  for (int k = 0; k < kBoxes; ++k) {
    const int neighbours = (k > 0 ? 1 : 0) + (k + 1 < kBoxes ? 1 : 0);
    EXPECT_EQ(touching[static_cast<std::size_t>(k)], 1 + neighbours) << "box " << k;
  }
}

// Continuous collision (issue 14): a 5 cm ball at 300 m/s crosses 1.25 m per substep, a 2 cm wall
// would be missed by any test of overlap at the substep's end.
Real ballAfterAThinWall(const bool continuous, const Real restitution) {
  World world(config(0.0));
  BodySettings settings;
  settings.continuous = continuous;
  EXPECT_TRUE(world.setBodySettings(settings));
  BoxCollider wall;
  wall.center = Vec3(2.0, 0.0, 0.0);
  wall.half_extents = Vec3(0.01, 1.0, 1.0);
  wall.material = Material{restitution, 0.0};
  EXPECT_TRUE(world.addCollider(wall).isOk());
  BodySpec ball = body(sphere(0.05, Material{restitution, 0.0}), 0.1, Vec3::Zero());
  ball.linear_velocity = Vec3(300.0, 0.0, 0.0);
  const BodyId id = *world.addBody(ball);
  for (int step = 0; step < 30; ++step) world.step();
  const std::size_t i = *world.bodies().find(id);
  return world.bodies().position(i).x();
}

TEST(BodyContact, AFastBallStopsAtAThinWall) {
  const Real x = ballAfterAThinWall(true, 0.0);
  std::printf("[ ccd ] ball at 300 m/s against a 2 cm wall: x = %.6f (face at 1.99)\n", x);
  EXPECT_NEAR(x, 1.99 - 0.05, 1e-3);
  EXPECT_GT(ballAfterAThinWall(false, 0.0), 2.0);  // without it the ball passes through
}

TEST(BodyContact, AFastBallBouncesOffAThinWallAtItsSpeed) {
  World world(config(0.0));
  BoxCollider wall;
  wall.center = Vec3(2.0, 0.0, 0.0);
  wall.half_extents = Vec3(0.01, 1.0, 1.0);
  wall.material = Material{1.0, 0.0};
  ASSERT_TRUE(world.addCollider(wall).isOk());
  BodySpec ball = body(sphere(0.05, Material{1.0, 0.0}), 0.1, Vec3::Zero());
  ball.linear_velocity = Vec3(300.0, 0.0, 0.0);
  const BodyId id = *world.addBody(ball);
  for (int step = 0; step < 3; ++step) world.step();
  const std::size_t i = *world.bodies().find(id);
  const Vec3 v = world.bodies().linearVelocity(i);
  const Real x = world.bodies().position(i).x();
  std::printf("[ ccd ] elastic ball back at v = %.4f m/s, x = %.5f after 3 steps\n", v.x(), x);
  EXPECT_NEAR(v.x(), -300.0, 1e-6 * 300.0);
  // Hit at t = 1.94 / 300 s, then back: x = 1.94 - 300 (3 dt - t).
  EXPECT_NEAR(x, 1.94 - 300.0 * (3.0 / 60.0 - 1.94 / 300.0), 1e-6);
}

// No gravity, the body solver at `substeps`.
World weightlessWorld(const int substeps) {
  World world(config(0.0));
  BodySettings settings;
  settings.substeps = substeps;
  EXPECT_TRUE(world.setBodySettings(settings));
  return world;
}

// A fixed 3 cm ball at the origin.
void addFixedBall(World& world, const Material& material = {0.0, 0.5}) {
  BodySpec resting = body(sphere(0.03, material), 0.1, Vec3::Zero());
  resting.type = BodyType::kFixed;
  EXPECT_TRUE(world.addBody(resting).isOk());
}

// A 3 cm ball falling at 11 m/s past what is at the origin, 1 cm wide of a 3 cm ball there, 15 cm
// above.
BodyId addBallFallingPastTheOrigin(World& world) {
  BodySpec falling = body(sphere(0.03), 0.1, Vec3(0.07, 0.0, 0.15));
  falling.linear_velocity = Vec3(0.0, 0.0, -11.0);
  return *world.addBody(falling);
}

BodyId addBallFallingPastABall(World& world) {
  addFixedBall(world);
  return addBallFallingPastTheOrigin(world);
}

// A ball that met nothing on its way.
void expectStillFalling(const World& world, const BodyId id) {
  const std::size_t i = *world.bodies().find(id);
  EXPECT_EQ(world.bodies().linearVelocity(i), Vec3(0.0, 0.0, -11.0));
  EXPECT_EQ(world.bodies().angularVelocity(i), Vec3::Zero());
}

// A speculative contact made where a fast pair starts stopped a ball on a plane across its fall
// that the other ball never reaches (swept_contact.h): this one, passing 1 cm wide of a ball at
// rest, left at 4.0 m/s sideways and 53 rad/s.
TEST(BodyContact, AFastBallFallingPastAnotherKeepsItsPath) {
  World world(config(0.0));
  const BodyId id = addBallFallingPastABall(world);
  for (int step = 0; step < 3; ++step) world.step();
  expectStillFalling(world, id);
  EXPECT_NEAR(world.bodies().position(*world.bodies().find(id)).z(), 0.15 - 11.0 * 3.0 / 60.0,
              1e-12);
}

// And one pushed towards the ball it passes within the step (here by a sideways gravity of
// 300 m/s^2, 2.8 cm by the time they are level) meets it: the pair's contact is the plane they
// pass across, not none. Without one, it ended the first step 1.6 cm into the ball and went on
// through it.
TEST(BodyContact, AFastBallPushedTowardsABallItPassesDoesNotGoThroughIt) {
  WorldConfig pushed = config(0.0);
  pushed.gravity = Vec3(-300.0, 0.0, 0.0);
  World world(pushed);
  const BodyId id = addBallFallingPastABall(world);
  for (int step = 0; step < 3; ++step) {
    world.step();
    const Vec3 p = world.bodies().position(*world.bodies().find(id));
    std::printf("[ swept ] step %d: centre at (%.4f, %.4f, %.4f), %.5f m from the other's\n", step,
                p.x(), p.y(), p.z(), p.norm());
    EXPECT_GT(p.norm(), 0.06 - world.bodySettings().linear_slop) << "step " << step;
  }
}

// And one that meets it on the way lands where they touch, along the line of their centres then.
TEST(BodyContact, AFastBallMeetsABallItFallsOntoAlongTheTouchNormal) {
  World world(config(0.0));
  addFixedBall(world, Material{0.0, 0.0});
  const Real side = 0.06 * std::sqrt(0.5);
  BodySpec falling = body(sphere(0.03, Material{0.0, 0.0}), 0.1, Vec3(side, 0.0, side + 0.12));
  falling.linear_velocity = Vec3(0.0, 0.0, -11.0);
  const BodyId id = *world.addBody(falling);
  world.step();
  const std::size_t i = *world.bodies().find(id);
  // Frictionless and e = 0: the part of (0, 0, -11) along (1, 0, 1) / sqrt(2) goes.
  const Vec3 expected(5.5, 0.0, -5.5);
  const Vec3 v = world.bodies().linearVelocity(i);
  std::printf("[ swept ] v (%.4f %.4f %.4f), expected (%.4f %.4f %.4f)\n", v.x(), v.y(), v.z(),
              expected.x(), expected.y(), expected.z());
  EXPECT_LT((v - expected).norm(), 0.1);
}

// With friction, the touching points are what the friction turns the ball about: at 45 degrees
// on a ball at rest, mu 0.5 holds the point (it needs 2/7 of the tangential speed's momentum, mu
// gives 1/2), so the ball leaves rolling along the tangent at 5/7 of v sin 45 and w = v / r.
// With its contact made where the step began (1.8 cm apart) it left at 1.936 m/s, 12 degrees off
// the tangent, turning at 49.6 rad/s; with the touch's normal but anchored midway across that gap,
// at 2.493 m/s and 65.4 rad/s. (At one substep, which the touch falls inside, it leaves at
// 2.43 m/s, 24 degrees off the tangent: not asserted here.)
TEST(BodyContact, AFastBallFallingOnABallObliquelyLeavesRolling) {
  for (const int substeps : {2, 4, 8}) {
    World world = weightlessWorld(substeps);
    constexpr Real kRadius = 0.03;
    constexpr Real kSpeed = 4.4;
    BodySpec resting = body(sphere(kRadius), 0.1, Vec3::Zero());
    resting.type = BodyType::kFixed;
    ASSERT_TRUE(world.addBody(resting).isOk());
    const Real side = 2.0 * kRadius * std::sqrt(0.5);
    BodySpec falling = body(sphere(kRadius), 0.1, Vec3(side, 0.0, side + 0.023));
    falling.linear_velocity = Vec3(0.0, 0.0, -kSpeed);
    const BodyId id = *world.addBody(falling);
    for (int step = 0; step < 3; ++step) world.step();
    const std::size_t i = *world.bodies().find(id);
    const Vec3 v = world.bodies().linearVelocity(i);
    const Vec3 w = world.bodies().angularVelocity(i);
    const Real rolling = 5.0 / 7.0 * kSpeed * std::sqrt(0.5);
    std::printf(
        "[ swept ] %d substeps: |v| %.4f (rolling %.4f), off the tangent %.2e rad, "
        "w %.3f (v / r %.3f)\n",
        substeps, v.norm(), rolling, angleBetween(v, Vec3(1.0, 0.0, -1.0)), w.y(),
        rolling / kRadius);
    EXPECT_NEAR(v.norm(), rolling, 0.01 * rolling) << substeps << " substeps";
    EXPECT_LT(angleBetween(v, Vec3(1.0, 0.0, -1.0)), 1e-2) << substeps << " substeps";
    EXPECT_NEAR(w.y(), rolling / kRadius, 0.01 * rolling / kRadius) << substeps << " substeps";
  }
}

// The same ghost came between bodies and particles, and bodies and colliders, whose contacts were
// still made where the pair starts.
ParticleSpec fastParticle(const Vec3& position) {
  ParticleSpec spec;
  spec.position = position;
  spec.velocity = Vec3(0.0, 0.0, -11.0);
  spec.inverse_mass = 10.0;
  spec.radius = 0.03;
  return spec;
}

Vec3 particleVelocity(const World& world, const ParticleId id) {
  return world.particles().velocities().col(*world.particles().find(id));
}

// This particle left at 6.37 m/s sideways.
TEST(BodyContact, AFastParticleFallingPastABallKeepsItsPath) {
  World world(config(0.0));
  addFixedBall(world);
  const ParticleId id = *world.addParticle(fastParticle(Vec3(0.07, 0.0, 0.15)));
  for (int step = 0; step < 3; ++step) world.step();
  EXPECT_EQ(particleVelocity(world, id), Vec3(0.0, 0.0, -11.0));
  const Vec3 x = world.particles().positions().col(*world.particles().find(id));
  EXPECT_NEAR(x.z(), 0.15 - 11.0 * 3.0 / 60.0, 1e-12);
}

// Both left at 2.63 m/s sideways, the particle pushed out of the ball's way.
TEST(BodyContact, AFastBallFallingPastAParticleLeavesItBe) {
  World world(config(0.0));
  ParticleSpec resting = fastParticle(Vec3::Zero());
  resting.velocity = Vec3::Zero();
  const ParticleId particle = *world.addParticle(resting);
  const BodyId ball = addBallFallingPastTheOrigin(world);
  for (int step = 0; step < 3; ++step) world.step();
  expectStillFalling(world, ball);
  EXPECT_EQ(particleVelocity(world, particle), Vec3::Zero());
}

// This ball left at (4.13, 0, 1.38) m/s: sideways and up.
TEST(BodyContact, AFastBallFallingPastABoxColliderKeepsItsPath) {
  World world(config(0.0));
  BoxCollider cube;
  cube.half_extents = Vec3::Constant(0.03);
  ASSERT_TRUE(world.addCollider(cube).isOk());
  const BodyId id = addBallFallingPastTheOrigin(world);
  for (int step = 0; step < 3; ++step) world.step();
  expectStillFalling(world, id);
}

// Met where the integrator had already moved it for the substep, this particle stopped 16 cm
// short of the ball at 1 substep, above where it started; at 2 and 4 it was still 2 cm above,
// coming down at 0.6 m/s, after three steps.
TEST(BodyContact, AFastParticleLandsOnABallWhereTheyTouch) {
  for (const int substeps : {1, 2, 4}) {
    World world = weightlessWorld(substeps);
    addFixedBall(world);
    const ParticleId id = *world.addParticle(fastParticle(Vec3(0.0, 0.0, 0.2)));
    ASSERT_TRUE(world.setParticleMaterial(id, Material{0.0, 0.5}));
    for (int step = 0; step < 3; ++step) world.step();
    const Vec3 x = world.particles().positions().col(*world.particles().find(id));
    EXPECT_NEAR(x.z(), 0.06, 1e-3) << substeps << " substeps";
    EXPECT_LT(particleVelocity(world, id).norm(), 1e-6) << substeps << " substeps";
  }
}

// One that meets the ball on the way lands where they touch: frictionless and e = 0, the part of
// its velocity along the line of the centres then, (1, 0, 1) / sqrt(2), goes.
TEST(BodyContact, AFastParticleMeetsABallItFallsOntoAlongTheTouchNormal) {
  World world(config(0.0));
  addFixedBall(world, Material{0.0, 0.0});
  const Real side = 0.06 * std::sqrt(0.5);
  const ParticleId id = *world.addParticle(fastParticle(Vec3(side, 0.0, side + 0.12)));
  ASSERT_TRUE(world.setParticleMaterial(id, Material{0.0, 0.0}));
  world.step();
  const Vec3 v = particleVelocity(world, id);
  std::printf("[ swept ] particle v (%.4f %.4f %.4f), expected (5.5 0 -5.5)\n", v.x(), v.y(),
              v.z());
  EXPECT_LT((v - Vec3(5.5, 0.0, -5.5)).norm(), 0.1);
}

// The ground (of `ground`), with particle collisions on (friction 0.3): a world for grains.
World groundForGrains(const Material& ground = Material{0.0, 0.5}) {
  World world(config());
  addGround(world, ground);
  CollisionSettings collisions;
  collisions.particle_collisions = true;
  collisions.particle_friction = 0.3;
  EXPECT_TRUE(world.setCollisionSettings(collisions).isOk());
  return world;
}

// A 0.5 m box of 20 kg on the ground, particle collisions on, and grains of 50 g at `centres`.
World grainsOnABox(const std::vector<Vec3>& centres) {
  World world = groundForGrains();
  EXPECT_TRUE(world.addBody(body(box(Vec3::Constant(0.25)), 20.0, Vec3(0.0, 0.0, 0.25))).isOk());
  for (const Vec3& centre : centres) addGrain(world, centre);
  return world;
}

struct GrainMotion {
  Real fastest = 0.0;
  Real lowest = std::numeric_limits<Real>::infinity();
  Real highest = -std::numeric_limits<Real>::infinity();
};

// The grains' fastest speed and their lowest and highest centres over `steps` frames.
GrainMotion watchGrains(World& world, const int steps) {
  GrainMotion motion;
  for (int step = 0; step < steps; ++step) {
    world.step();
    const auto x = world.particles().positions();
    const auto v = world.particles().velocities();
    for (Eigen::Index i = 0; i < v.cols(); ++i) {
      motion.fastest = std::max(motion.fastest, v.col(i).norm());
      motion.lowest = std::min(motion.lowest, x(2, i));
      motion.highest = std::max(motion.highest, x(2, i));
    }
  }
  return motion;
}

// A row of grains touching each other on a box: the grains' resting contacts with each other are
// solved as rows, and each grain followed the box's impulse on it twice (the body solver moved it,
// then the particles' position stage moved it again by the velocity it found changed since its own
// solve). Each rose beta h dv every few substeps and fell back: the grains left every frame at up
// to 0.041 m/s, never at rest.
TEST(BodyContact, GrainsSideBySideRestOnABox) {
  std::vector<Vec3> row;
  for (int k = 0; k < 5; ++k) row.emplace_back(-0.2 + 0.099 * k, 0.0, 0.5 + kGrainRadius);
  World world = grainsOnABox(row);
  for (int step = 0; step < 120; ++step) world.step();
  const GrainMotion motion = watchGrains(world, 60);
  EXPECT_LT(motion.fastest, 1e-6);
  EXPECT_NEAR(motion.lowest, 0.5 + kGrainRadius, 1e-4);
  EXPECT_NEAR(motion.highest, 0.5 + kGrainRadius, 1e-4);
}

// Grains stacked on a box: the body solver carries the upper grains' weight down to the box (their
// contacts are its rows too). The particle solver, which runs first, saw the lowest grain free:
// the grains fell together there, the body rows then stopped the lowest alone, and the positions
// stage pushed it into the box as the others closed on it: 3.7 mm deep, the grains leaving frames
// at 0.12 m/s (2.2 mm with the follow counted twice).
TEST(BodyContact, AStackOfGrainsRestsOnABoxWithoutSinkingIntoIt) {
  const Real bottom = 0.5 + kGrainRadius;
  const Real gap = 2.0 * kGrainRadius;
  World world = grainsOnABox(
      {Vec3(0.0, 0.0, bottom), Vec3(0.0, 0.0, bottom + gap), Vec3(0.0, 0.0, bottom + 2.0 * gap)});
  for (int step = 0; step < 180; ++step) world.step();
  const GrainMotion motion = watchGrains(world, 60);
  EXPECT_LT(motion.fastest, 1e-6);
  EXPECT_GT(motion.lowest, bottom - 1e-4);
  EXPECT_LT(motion.highest, bottom + 2.0 * gap + 1e-4);
}

// Grains of radius r and inverse mass 1 / m at `centres`, all moving at `velocity`.
void addMovingGrains(World& world, const std::vector<Vec3>& centres, const Vec3& velocity,
                     const Real radius = kGrainRadius, const Real inverse_mass = 20.0) {
  for (const Vec3& centre : centres) {
    ParticleSpec spec;
    spec.position = centre;
    spec.velocity = velocity;
    spec.radius = radius;
    spec.inverse_mass = inverse_mass;
    EXPECT_TRUE(world.addParticle(spec).isOk());
  }
}

// 400 grains strike a plate on the ground in the same substep. Each impact moved the plate as a
// free body flies, dp -= a h^2 / 2, and so the plate rose 400 times that: 2.3 cm.
TEST(BodyContact, APlateStruckByManyGrainsAtOnceIsNotLifted) {
  World world(config());
  addGround(world);
  CollisionSettings collisions;
  collisions.particle_restitution = 0.5;
  ASSERT_TRUE(world.setCollisionSettings(collisions).isOk());
  const BodyId plate = *world.addBody(body(box(Vec3(0.5, 0.5, 0.05)), 50.0, Vec3(0.0, 0.0, 0.05)));
  std::vector<Vec3> layer;
  for (int i = 0; i < 20; ++i) {
    for (int j = 0; j < 20; ++j) layer.emplace_back(-0.475 + 0.05 * i, -0.475 + 0.05 * j, 0.13);
  }
  addMovingGrains(world, layer, Vec3(0.0, 0.0, -3.0), 0.02, 50.0);
  Real highest = 0.0;
  for (int step = 0; step < 30; ++step) {
    world.step();
    highest = std::max(highest, world.bodies().position(*world.bodies().find(plate)).z());
  }
  EXPECT_LT(highest, 0.05 + 1e-5);
}

// A column of eight touching grains lands on a box (restitution 0.1). The lowest grain's contact
// bounced it in the first substep and then held nothing for the rest of the step, while the
// grains above drove it on: its centre went 12 cm below the box's face at 3 m/s. Then the
// particles' positions stage, which did not see the box, pushed it in while taking the column's
// overlaps out: 3.4 cm at 3 m/s, 8.4 cm at 6. With the box's surface there, and the body solver's
// move of it not counted as overlap, 0.9 and 1.0 mm (3.5 and 9.1 mm with the move counted).
TEST(BodyContact, AColumnOfGrainsLandingOnABoxStaysOnTop) {
  for (const Real speed : {3.0, 6.0}) {
    World world(config());
    addGround(world);
    CollisionSettings collisions;
    collisions.particle_collisions = true;
    collisions.particle_restitution = 0.1;
    collisions.particle_friction = 0.3;
    ASSERT_TRUE(world.setCollisionSettings(collisions).isOk());
    ASSERT_TRUE(world.addBody(body(box(Vec3::Constant(0.25)), 20.0, Vec3(0.0, 0.0, 0.25))).isOk());
    std::vector<Vec3> column;
    for (int k = 0; k < 8; ++k) column.emplace_back(0.0, 0.0, 0.56 + 2.0 * kGrainRadius * k);
    addMovingGrains(world, column, Vec3(0.0, 0.0, -speed));
    Real lowest = std::numeric_limits<Real>::infinity();
    for (int step = 0; step < 60; ++step) {
      world.step();
      lowest = std::min(lowest, world.particles().positions()(2, 0));
    }
    EXPECT_GT(lowest, 0.5 + kGrainRadius - 2e-3) << speed << " m/s";
  }
}

// The lowest grain's gap to the top face of the box `id` (0.5 m wide): + above it, - into it.
Real gapOverBox(const World& world, const BodyId id) {
  const std::size_t b = *world.bodies().find(id);
  return world.particles().positions()(2, 0) - kGrainRadius -
         (world.bodies().position(b).z() + 0.25);
}

// A box carrying a column of four grains falls 2 m onto the ground. The grains fall with it: the
// shock pass held them still in the ground's frame through the first step, so they fell a step
// behind the box, 5 cm above it when it landed. And they land with it: the positions stage
// pushed the lowest 3.6 cm into the box as the column landed.
TEST(BodyContact, GrainsRideAFallingBoxAndLandWithIt) {
  World world = groundForGrains();
  const BodyId id = *world.addBody(body(box(Vec3::Constant(0.25)), 20.0, Vec3(0.0, 0.0, 2.25)));
  for (int k = 0; k < 4; ++k) addGrain(world, Vec3(0.0, 0.0, 2.5 + kGrainRadius * (1 + 2 * k)));
  Real deepest = 0.0;
  Real widest_in_flight = 0.0;
  for (int step = 0; step < 120; ++step) {
    world.step();
    const Real gap = gapOverBox(world, id);
    deepest = std::min(deepest, gap);
    if (world.bodies().position(*world.bodies().find(id)).z() > 0.3) {
      widest_in_flight = std::max(widest_in_flight, gap);
    }
  }
  EXPECT_GT(deepest, -2e-3);
  EXPECT_LT(widest_in_flight, 1e-3);
}

// A grain on a box sliding at 3 m/s on a frictionless ground rides it (friction 0.3): braked in
// the ground's frame by the shock pass, it slid off the box's back within half a second.
TEST(BodyContact, AGrainRidesASlidingBox) {
  World world(config());
  addGround(world, Material{0.0, 0.0});
  CollisionSettings collisions;
  collisions.particle_friction = 0.3;
  ASSERT_TRUE(world.setCollisionSettings(collisions).isOk());
  BodySpec cart = body(box(Vec3(0.5, 0.5, 0.25)), 20.0, Vec3(0.0, 0.0, 0.25));
  cart.linear_velocity = Vec3(3.0, 0.0, 0.0);
  const BodyId id = *world.addBody(cart);
  addMovingGrains(world, {Vec3(0.0, 0.0, 0.5 + kGrainRadius)}, cart.linear_velocity);
  for (int step = 0; step < 60; ++step) world.step();
  const std::size_t b = *world.bodies().find(id);
  const Vec3 grain = world.particles().positions().col(0);
  EXPECT_NEAR(grain.x() - world.bodies().position(b).x(), 0.0, 0.01);
  EXPECT_NEAR(gapOverBox(world, id), 0.0, 1e-3);
  EXPECT_NEAR(world.particles().velocities()(0, 0), world.bodies().linearVelocity(b).x(), 0.01);
}

// A kinematic box lifts a column of four grains at 1 m/s: 3.9 mm into it before its surface
// followed it.
TEST(BodyContact, AKinematicBoxLiftsAColumnOfGrains) {
  World world = groundForGrains();
  BodySpec lift = body(box(Vec3::Constant(0.25)), 20.0, Vec3(0.0, 0.0, 0.25));
  lift.type = BodyType::kKinematic;
  lift.linear_velocity = Vec3(0.0, 0.0, 1.0);
  const BodyId id = *world.addBody(lift);
  for (int k = 0; k < 4; ++k) addGrain(world, Vec3(0.0, 0.0, 0.5 + kGrainRadius * (1 + 2 * k)));
  Real deepest = 0.0;
  for (int step = 0; step < 60; ++step) {
    world.step();
    deepest = std::min(deepest, gapOverBox(world, id));
  }
  EXPECT_GT(deepest, -2e-3);
  EXPECT_NEAR(gapOverBox(world, id), 0.0, 1e-3);
}

// A column of two grains rides a box pushed along frictionless ground at 1 m/s^2: the upper
// grain is carried by its friction on the lower one, which the body solver has alone (the pile
// rests on the moving box only). With that contact a push-only body row and the particle
// solver's friction (before session 31), the upper grain was left behind and fell onto the box
// (23 cm apart).
TEST(BodyContact, AColumnOfGrainsRidesABoxPushedAlongOnItsFriction) {
  World world = groundForGrains(Material{0.0, 0.0});
  BodySettings settings;
  settings.sleep = false;
  ASSERT_TRUE(world.setBodySettings(settings).isOk());
  const BodyId cart = *world.addBody(body(box(Vec3::Constant(0.25)), 20.0, Vec3(0.0, 0.0, 0.25)));
  addGrain(world, Vec3(0.0, 0.0, 0.5 + kGrainRadius));
  addGrain(world, Vec3(0.0, 0.0, 0.5 + 3.0 * kGrainRadius));
  for (int step = 0; step < 30; ++step) world.step();
  const std::size_t b = *world.bodies().find(cart);
  const Real acceleration = 1.0;
  Real widest = 0.0;
  for (int step = 0; step < 60; ++step) {
    ASSERT_TRUE(world
                    .addBodyForce(cart, Vec3((20.0 + 0.1) * acceleration, 0.0, 0.0),
                                  world.bodies().position(b))
                    .isOk());
    world.step();
    const auto x = world.particles().positions();
    widest = std::max(
        {widest, std::abs(x(0, 1) - x(0, 0)), std::abs(x(0, 0) - world.bodies().position(b).x())});
  }
  const Real v = world.bodies().linearVelocity(b).x();
  EXPECT_NEAR(v, acceleration * 1.0, 0.02);
  EXPECT_LT(widest, 1e-3);
  EXPECT_NEAR(world.particles().velocities()(0, 1), v, 1e-3);
  EXPECT_GT(world.particles().positions()(2, 1), 0.5 + 3.0 * kGrainRadius - 1e-3);
}

// A grain on an awake box is the body rows' (the positions stage only keeps it out of the box's
// surface): the report gives the body rows' impulse, its weight over a substep, and not the
// positions stage's none.
TEST(BodyContact, AGrainOnAnAwakeBoxReportsItsWeight) {
  World world = groundForGrains();
  BodySettings settings;
  settings.sleep = false;
  ASSERT_TRUE(world.setBodySettings(settings).isOk());
  ASSERT_TRUE(world.addBody(body(box(Vec3::Constant(0.25)), 20.0, Vec3(0.0, 0.0, 0.25))).isOk());
  addGrain(world, Vec3(0.0, 0.0, 0.5 + kGrainRadius));
  for (int step = 0; step < 60; ++step) world.step();
  const Real h = world.config().dt / world.substepsUsed();
  bool found = false;
  for (const BodyContactReport& report : world.bodyContacts()) {
    if (report.other != BodyContactReport::Other::kParticle) continue;
    found = true;
    Real normal = 0.0;
    for (const auto& point : report.points) normal += point.normal_impulse;
    EXPECT_NEAR(normal, 0.05 * kG * h, 1e-6);
  }
  EXPECT_TRUE(found);
}

// A grain resting on a fixed half-metre box on the ground; the box's id in `table`.
World grainOnAFixedBox(BodyId& table) {
  World world(config());
  addGround(world);
  BodySpec spec = body(box(Vec3::Constant(0.25)), 20.0, Vec3(0.0, 0.0, 0.25));
  spec.type = BodyType::kFixed;
  table = *world.addBody(spec);
  addGrain(world, Vec3(0.0, 0.0, 0.5 + kGrainRadius));
  return world;
}

// A grain on a body that does not move is the particle solver's (as on a collider): the report
// still gives the impulse that holds it, its weight over a substep.
TEST(BodyContact, AGrainOnAFixedBoxReportsItsWeight) {
  BodyId table;
  World world = grainOnAFixedBox(table);
  for (int step = 0; step < 60; ++step) world.step();
  const std::vector<BodyContactReport> reports = world.bodyContacts();
  ASSERT_EQ(reports.size(), 1u);
  ASSERT_EQ(reports[0].points.size(), 1u);
  const Real h = world.config().dt / world.substepsUsed();
  EXPECT_NEAR(reports[0].points[0].normal_impulse, 0.05 * kG * h, 1e-9);
  EXPECT_NEAR(world.particles().positions()(2, 0), 0.5 + kGrainRadius, 1e-3);
}

// The last body gone, the surface it lent the particle solver goes with it.
TEST(BodyContact, AGrainFallsWhenTheFixedBoxUnderItIsRemoved) {
  BodyId table;
  World world = grainOnAFixedBox(table);
  for (int step = 0; step < 30; ++step) world.step();
  ASSERT_TRUE(world.removeBody(table).isOk());
  for (int step = 0; step < 60; ++step) world.step();
  EXPECT_NEAR(world.particles().positions()(2, 0), kGrainRadius, 1e-3);
}

// Three grains stacked on a fixed box rest as they do on a box collider of the same size, to
// rounding: the particle solver takes the still body's surface before the grains' contacts with
// each other, as it takes the colliders' (a pile is held up from below). Taken after them, the
// lowest grain rested 0.11 mm deep at the particles' substep, not 1.5 um.
TEST(BodyContact, AColumnOfGrainsOnAFixedBoxRestsAsOnABoxCollider) {
  const auto column = [](const bool on_a_body) {
    World world = groundForGrains();
    if (on_a_body) {
      BodySpec spec =
          body(box(Vec3::Constant(0.25), Material{0.0, 0.5}), 20.0, Vec3(0.0, 0.0, 0.25));
      spec.type = BodyType::kFixed;
      EXPECT_TRUE(world.addBody(spec).isOk());
    } else {
      BoxCollider table;
      table.center = Vec3(0.0, 0.0, 0.25);
      table.half_extents = Vec3::Constant(0.25);
      table.material = Material{0.0, 0.5};
      EXPECT_TRUE(world.addCollider(table));
    }
    for (int k = 0; k < 3; ++k) addGrain(world, Vec3(0.0, 0.0, 0.5 + (2 * k + 1) * kGrainRadius));
    for (int step = 0; step < 240; ++step) world.step();
    EXPECT_EQ(world.substepsUsed(), 1);
    return Vec3(world.particles().positions().row(2).transpose());
  };
  const Vec3 on_collider = column(false);
  const Vec3 on_body = column(true);
  std::printf("[ column ] lowest grain %.3e m deep on the collider, %.3e on the fixed body\n",
              0.5 + kGrainRadius - on_collider.x(), 0.5 + kGrainRadius - on_body.x());
  EXPECT_LT((on_body - on_collider).cwiseAbs().maxCoeff(), 1e-9);
}

// A particle at 40 m/s strikes a fixed plate (no gravity, restitution 0.25 on both sides, no
// collider: the contact is a body row) in the second substep, 6.75 ms into the step, and leaves
// at 10 m/s from the plate's face: 1.06 + 10 (1/60 - 0.00675) = 1.159167 at the step's end. The
// body solver's impact moved it back to the touch, but only a body's position kept that: the
// particle turned where the substep began, 10 cm above the plate, and ended the step at 1.2883.
TEST(BodyContact, AFastParticleBouncesFromTheFaceOfAFixedPlate) {
  World world(config(0.0));
  BodySpec plate = body(box(Vec3(0.5, 0.5, 0.01), Material{0.25, 0.5}), 20.0, Vec3(0, 0, 1.0));
  plate.type = BodyType::kFixed;
  ASSERT_TRUE(world.addBody(plate).isOk());
  CollisionSettings collisions = world.collisionSettings();
  collisions.particle_restitution = 0.25;
  ASSERT_TRUE(world.setCollisionSettings(collisions).isOk());
  ParticleSpec spec;
  spec.position = Vec3(0.0, 0.0, 1.01 + kGrainRadius + 0.27);
  spec.velocity = Vec3(0.0, 0.0, -40.0);
  spec.radius = kGrainRadius;
  spec.inverse_mass = 20.0;
  ASSERT_TRUE(world.addParticle(spec));
  world.step();
  const Real touch = 0.27 / 40.0;
  EXPECT_NEAR(world.particles().velocities()(2, 0), 10.0, 1e-9);
  EXPECT_NEAR(world.particles().positions()(2, 0),
              1.01 + kGrainRadius + 10.0 * (world.config().dt - touch), 1e-9);
}

TEST(BodyContact, AFastBallStopsAtAThinFixedBody) {
  World world(config(0.0));
  BodySpec wall = body(box(Vec3(0.01, 1.0, 1.0), Material{0.0, 0.0}), 1.0, Vec3(2.0, 0.0, 0.0));
  wall.type = BodyType::kFixed;
  ASSERT_TRUE(world.addBody(wall).isOk());
  BodySpec ball = body(sphere(0.05, Material{0.0, 0.0}), 0.1, Vec3::Zero());
  ball.linear_velocity = Vec3(300.0, 0.0, 0.0);
  const BodyId id = *world.addBody(ball);
  for (int step = 0; step < 30; ++step) world.step();
  EXPECT_NEAR(world.bodies().position(*world.bodies().find(id)).x(), 1.99 - 0.05, 1e-3);
}

TEST(BodyContact, AFastBoxLandsOnTheGround) {
  World world(config());
  addGround(world);
  BodySpec falling = body(box(Vec3(0.5, 0.05, 0.05)), 1.0, Vec3(0.0, 0.0, 3.0));
  falling.linear_velocity = Vec3(0.0, 0.0, -150.0);
  const BodyId id = *world.addBody(falling);
  for (int step = 0; step < 60; ++step) world.step();
  const std::size_t i = *world.bodies().find(id);
  EXPECT_NEAR(world.bodies().position(i).z(), 0.05, 1e-3);
}

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
