// Force generators on bodies (issue 14): springs and bungees between points of bodies, particles
// and the world, drag and buoyancy on bodies, checked against their closed forms; the particle at
// a spring's end exchanges momentum exactly under every integrator; they are validated, removed
// with their bodies and particles, and keep the bodies they join awake.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "../bodies/body_scenes.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

using namespace test_bodies;

constexpr Real kPi = 3.14159265358979323846;

std::size_t dense(const World& world, const BodyId id) { return *world.bodies().find(id); }

TEST(PointSprings, ABodyHangingFromTheWorldOscillatesAtItsPeriod) {
  // m = 2 kg on k = 200 N/m from an anchor 1 m above its centre, released at the rest length:
  // it oscillates about L + m g / k below the anchor with amplitude m g / k and period
  // 2 pi sqrt(m / k) = 0.6283 s.
  World world(config());
  const Real m = 2.0;
  const Real k = 200.0;
  const BodyId id = *world.addBody(body(sphere(0.1), m, Vec3(0.0, 0.0, 2.0)));
  const Vec3 anchor(0.0, 0.0, 3.0);
  ASSERT_TRUE(world.addBodyGenerator(
      PointSpring::between(JointEnd::onBody(id), JointEnd::inWorld(anchor), k, 1.0)));
  const Real amplitude = m * kG / k;
  const Real centre = 2.0 - amplitude;
  std::vector<Real> upward_crossings;
  Real lowest = 2.0;
  Real highest = 0.0;
  Real previous = 2.0 - centre;
  for (int step = 0; step < 600; ++step) {
    world.step();
    const Real z = world.bodies().position(dense(world, id)).z();
    lowest = std::min(lowest, z);
    highest = std::max(highest, z);
    const Real offset = z - centre;
    if (previous < 0.0 && offset >= 0.0) {
      // Linear interpolation of the crossing inside the step.
      const Real fraction = -previous / (offset - previous);
      upward_crossings.push_back((step + fraction) * world.config().dt);
    }
    previous = offset;
  }
  ASSERT_GE(upward_crossings.size(), 10u);
  const Real period =
      (upward_crossings.back() - upward_crossings.front()) / (upward_crossings.size() - 1);
  EXPECT_NEAR(period, 2.0 * kPi * std::sqrt(m / k), 0.005 * 2.0 * kPi * std::sqrt(m / k));
  EXPECT_NEAR(highest, centre + amplitude, 0.01 * amplitude);
  EXPECT_NEAR(lowest, centre - amplitude, 0.01 * amplitude);
}

TEST(PointSprings, AForceAtAPointOffTheCentreTurnsTheBody) {
  // No gravity: a spring pulls a 1 kg unit cube along +x at r = (0, 0.5, 0) from its centre.
  // F t moves the centre and I^-1 (r x F) t = (0, 0, -3 F t) turns it: dw_z / dv_x = -3.
  World world(config(0.0));
  const BodyId id = *world.addBody(body(box(Vec3::Constant(0.5)), 1.0, Vec3::Zero()));
  ASSERT_TRUE(world.addBodyGenerator(PointSpring::between(JointEnd::onBody(id, Vec3(0.0, 0.5, 0.0)),
                                                          JointEnd::inWorld(Vec3(5.0, 0.5, 0.0)),
                                                          1.0, 0.0)));
  world.step();
  const std::size_t i = dense(world, id);
  const Vec3 v = world.bodies().linearVelocity(i);
  const Vec3 w = world.bodies().angularVelocity(i);
  EXPECT_NEAR(v.x(), 5.0 * world.config().dt, 0.01 * 5.0 * world.config().dt);
  EXPECT_NEAR(w.z() / v.x(), -3.0, 0.01);
  EXPECT_NEAR(w.x(), 0.0, 1e-12);
  EXPECT_NEAR(w.y(), 0.0, 1e-12);
}

class ParticleToBody : public ::testing::TestWithParam<Integrator> {};

TEST_P(ParticleToBody, ExchangeMomentumExactlyUnderEveryIntegrator) {
  // No gravity: a 0.5 kg particle on a damped spring to a point of a 2 kg box, both moving. The
  // particle feels the spring's force of the substep's start under its own integrator and the
  // box the opposite: their total momentum stays what it was, to rounding.
  WorldConfig c = config(0.0);
  c.integrator = GetParam();
  World world(c);
  BodySpec box_spec = body(box(Vec3(0.5, 0.25, 0.25)), 2.0, Vec3::Zero());
  box_spec.linear_velocity = Vec3(0.3, -0.2, 0.1);
  box_spec.angular_velocity = Vec3(0.0, 0.5, 1.0);
  const BodyId box_id = *world.addBody(box_spec);
  ParticleSpec particle;
  particle.position = Vec3(2.0, 0.3, 0.0);
  particle.velocity = Vec3(-0.5, 1.0, 0.2);
  particle.inverse_mass = 2.0;
  const ParticleId particle_id = *world.addParticle(particle);
  ASSERT_TRUE(world.addBodyGenerator(
      PointSpring::between(JointEnd::onBody(box_id, Vec3(0.5, 0.0, 0.0)),
                           JointEnd::atParticle(particle_id), 40.0, 1.0, 0.3)));
  const Vec3 before = world.linearMomentum();
  const Vec3 particle_before = 0.5 * particle.velocity;
  for (int step = 0; step < 240; ++step) world.step();
  const Vec3 after = world.linearMomentum();
  EXPECT_LT((after - before).norm(), 1e-12 * (1.0 + before.norm())) << (after - before).transpose();
  const std::size_t p = *world.particles().find(particle_id);
  const Vec3 particle_after = 0.5 * Vec3(world.particles().velocities().col(p));
  EXPECT_GT((particle_after - particle_before).norm(), 0.1);  // the spring did act
  EXPECT_EQ(world.divergenceCount(), 0u);
}

INSTANTIATE_TEST_SUITE_P(AllIntegrators, ParticleToBody,
                         ::testing::Values(Integrator::kExplicitEuler,
                                           Integrator::kSemiImplicitEuler,
                                           Integrator::kPositionVerlet, Integrator::kVelocityVerlet,
                                           Integrator::kRk4, Integrator::kImplicitEuler));

TEST(PointSprings, TwoBodiesKeepTheirMomentumAndTheirEnergy) {
  // No gravity: two boxes on an undamped spring between their corners spin and oscillate (never
  // touching: a contact would take energy); the
  // spring's forces are equal and opposite (momentum to rounding) and the energy, kinetic plus
  // elastic, swings by a few percent (semi-implicit Euler's bounded error, w h about 0.05 for the
  // corners' effective mass) without a trend: its mean over the last second of 10 s is that
  // over the first to 0.5 %.
  World world(config(0.0));
  BodySpec a = body(box(Vec3::Constant(0.5)), 1.0, Vec3::Zero());
  a.angular_velocity = Vec3(0.0, 0.0, 0.7);
  BodySpec b = body(box(Vec3::Constant(0.5)), 3.0, Vec3(5.0, 0.0, 0.0));
  b.linear_velocity = Vec3(0.0, 0.4, 0.0);
  const BodyId ida = *world.addBody(a);
  const BodyId idb = *world.addBody(b);
  ASSERT_TRUE(world.addBodyGenerator(
      PointSpring::between(JointEnd::onBody(ida, Vec3(0.5, 0.5, 0.5)),
                           JointEnd::onBody(idb, Vec3(-0.5, 0.5, 0.0)), 20.0, 3.5)));
  const Real energy = world.kineticEnergy() + world.springEnergy();
  EXPECT_GT(world.springEnergy(), 0.0);
  const Vec3 momentum = world.linearMomentum();
  Real first = 0.0;
  Real last = 0.0;
  Real swing = 0.0;
  for (int step = 0; step < 600; ++step) {
    world.step();
    ASSERT_LT((world.linearMomentum() - momentum).norm(), 1e-12);
    const Real now = world.kineticEnergy() + world.springEnergy();
    swing = std::max(swing, std::abs(now - energy) / energy);
    if (step < 60) first += now / 60.0;
    if (step >= 540) last += now / 60.0;
  }
  std::printf("[ energy ] swing %.4f, first second %.6f J, last second %.6f J\n", swing, first,
              last);
  EXPECT_LT(swing, 0.03);
  EXPECT_NEAR(last, first, 0.005 * first);
}

TEST(PointSprings, ABungeePullsOnlyWhenStretched) {
  // No gravity: a body 0.5 m from the anchor of a 1 m bungee feels nothing; moved to 2 m it is
  // pulled back.
  World world(config(0.0));
  const BodyId id = *world.addBody(body(sphere(0.1), 1.0, Vec3(0.5, 0.0, 0.0)));
  ASSERT_TRUE(world.addBodyGenerator(
      PointSpring::between(JointEnd::onBody(id), JointEnd::inWorld(Vec3::Zero()), 10.0, 1.0)
          .pullingOnly()));
  EXPECT_EQ(world.springEnergy(), 0.0);
  world.step();
  EXPECT_EQ(world.bodies().linearVelocity(dense(world, id)), Vec3::Zero());
  ASSERT_TRUE(world.setBodyPose(id, Transform{Vec3(2.0, 0.0, 0.0), Quat::Identity()}));
  EXPECT_NEAR(world.springEnergy(), 0.5 * 10.0 * 1.0 * 1.0, 1e-12);
  world.step();
  EXPECT_LT(world.bodies().linearVelocity(dense(world, id)).x(), 0.0);
}

TEST(PointSprings, ASpringTooStiffForTheSubstepsDivergesAndIsReported) {
  // k = 1e6 N/m on 1 kg: omega h = 1000 / 240 = 4.2 at the default 4 substeps, beyond
  // semi-implicit Euler's 2. The amplitude grows every substep until the body passes the runaway
  // speed: a divergence event that names the body, and under kPause the world stops there.
  WorldConfig c = config(0.0);
  c.divergence_policy = DivergencePolicy::kPause;
  World world(c);
  const BodyId id = *world.addBody(body(sphere(0.1), 1.0, Vec3(0.01, 0.0, 0.0)));
  ASSERT_TRUE(world.addBodyGenerator(
      PointSpring::between(JointEnd::onBody(id), JointEnd::inWorld(Vec3::Zero()), 1e6, 0.0)));
  int steps = 0;
  while (!world.paused() && steps < 120) {
    world.step();
    ++steps;
  }
  ASSERT_TRUE(world.paused()) << "no divergence reported in " << steps << " steps";
  ASSERT_TRUE(world.lastDivergence().has_value());
  EXPECT_EQ(world.lastDivergence()->body, id);
  EXPECT_NE(world.lastDivergence()->what.find("runaway"), std::string::npos)
      << world.lastDivergence()->what;
  // At 32 substeps (omega h = 0.52) the same spring is stable and nothing is reported.
  World fine(config(0.0));
  BodySettings settings = fine.bodySettings();
  settings.substeps = 32;
  ASSERT_TRUE(fine.setBodySettings(settings));
  const BodyId calm = *fine.addBody(body(sphere(0.1), 1.0, Vec3(0.01, 0.0, 0.0)));
  ASSERT_TRUE(fine.addBodyGenerator(
      PointSpring::between(JointEnd::onBody(calm), JointEnd::inWorld(Vec3::Zero()), 1e6, 0.0)));
  for (int step = 0; step < 120; ++step) fine.step();
  EXPECT_EQ(fine.divergenceCount(), 0u);
  EXPECT_LT(fine.bodies().position(dense(fine, calm)).norm(), 0.0101);
}

TEST(PointSprings, TheStabilityReportNamesASpringTooStiffForTheBodiesSubsteps) {
  // The spring of the test above: omega = sqrt(k / m) = 1000 rad/s at the centre of mass, so
  // omega h = 4.17 at 4 substeps of 1/60 s, beyond 2; stable from floor(dt / (2 / omega)) + 1 = 9
  // substeps.
  World world(config(0.0));
  const BodyId id = *world.addBody(body(sphere(0.1), 1.0, Vec3(0.01, 0.0, 0.0)));
  const GeneratorId stiff = *world.addBodyGenerator(
      PointSpring::between(JointEnd::onBody(id), JointEnd::inWorld(Vec3::Zero()), 1e6, 0.0));
  const StabilityReport& report = world.stabilityReport();
  EXPECT_FALSE(report.stable);
  EXPECT_EQ(report.generator, stiff);
  EXPECT_NEAR(report.omega, 1000.0, 1e-9);
  EXPECT_NEAR(report.omega_h, 1000.0 / 240.0, 1e-9);
  EXPECT_EQ(report.limit, 2.0);
  EXPECT_EQ(report.substeps_needed, 9);
  EXPECT_NE(report.message.find("point spring"), std::string::npos) << report.message;

  // Off the centre of mass the body turns too: 1/m_eff along any line is at most
  // 1/m + |r|^2 / I_min, and that bound is the one reported.
  World turning(config(0.0));
  const BodyId plank = *turning.addBody(body(box(Vec3(0.5, 0.25, 0.1)), 2.0, Vec3::Zero()));
  const Vec3 corner(0.5, 0.25, 0.1);
  ASSERT_TRUE(turning.addBodyGenerator(PointSpring::between(
      JointEnd::onBody(plank, corner), JointEnd::inWorld(Vec3(1.0, 1.0, 1.0)), 5e4, 0.5)));
  const std::size_t i = dense(turning, plank);
  const Real mobility =
      0.5 + corner.squaredNorm() / turning.bodies().principalInertia(i).minCoeff();
  EXPECT_NEAR(turning.stabilityReport().omega, std::sqrt(5e4 * mobility), 1e-9);

  // A particle at the other end adds its 1/m; a weak spring is stable and says nothing.
  World mixed(config(0.0));
  const BodyId ball = *mixed.addBody(body(sphere(0.1), 1.0, Vec3::Zero()));
  ParticleSpec particle;
  particle.position = Vec3(1.0, 0.0, 0.0);
  particle.inverse_mass = 2.0;
  const ParticleId p = *mixed.addParticle(particle);
  ASSERT_TRUE(mixed.addBodyGenerator(
      PointSpring::between(JointEnd::onBody(ball), JointEnd::atParticle(p), 50.0, 1.0)));
  EXPECT_TRUE(mixed.stabilityReport().stable) << mixed.stabilityReport().message;
  EXPECT_NEAR(mixed.stabilityReport().omega, std::sqrt(50.0 * 3.0), 1e-12);
  EXPECT_TRUE(mixed.stabilityReport().message.empty());
}

TEST(PointSprings, AutoSubstepTakesTheSubstepsAStiffSpringOnABodyNeeds) {
  // With auto_substep the world steps the stiff spring above with the substeps that keep it
  // within the margin, and nothing runs away (without its spring in the report it diverged).
  WorldConfig c = config(0.0);
  c.auto_substep = true;
  World world(c);
  const BodyId id = *world.addBody(body(sphere(0.1), 1.0, Vec3(0.01, 0.0, 0.0)));
  ASSERT_TRUE(world.addBodyGenerator(
      PointSpring::between(JointEnd::onBody(id), JointEnd::inWorld(Vec3::Zero()), 1e6, 0.0)));
  Real farthest = 0.0;
  for (int step = 0; step < 120; ++step) {
    world.step();
    farthest = std::max(farthest, world.bodies().position(dense(world, id)).norm());
  }
  EXPECT_EQ(world.divergenceCount(), 0u);
  EXPECT_EQ(world.substepsUsed(), world.stabilityReport().substeps_with_margin);
  EXPECT_EQ(world.substepsUsed(), 10);  // omega h <= 0.9 * 2: floor(dt omega / 1.8) + 1
  // Semi-implicit Euler keeps x^2 - h x v + v^2 / omega^2: from rest at x0 it swings out to at most
  // x0 / sqrt(1 - (omega h / 2)^2), 1.8 x0 at omega h = 1000 / 600.
  const Real omega_h = 1000.0 / 600.0;
  EXPECT_LT(farthest, 0.01 / std::sqrt(1.0 - 0.25 * omega_h * omega_h) * (1.0 + 1e-6));
}

TEST(BodyDrag, AFallingBodyReachesItsTerminalSpeed) {
  // Linear drag k1 on 1 kg: v_t = m g / k1; quadratic k2: v_t = sqrt(m g / k2). Turning drag c
  // on a sphere (I = 2/5 m r^2): w(t) = w0 exp(-c t / I), 1 % at 1 s.
  World world(config());
  BodySpec linear = body(sphere(0.5), 1.0, Vec3(0.0, 0.0, 0.0));
  linear.angular_velocity = Vec3(0.0, 0.0, 2.0);
  BodySpec quadratic = body(sphere(0.5), 1.0, Vec3(5.0, 0.0, 0.0));
  const BodyId lin = *world.addBody(linear);
  const BodyId quad = *world.addBody(quadratic);
  BodyDrag drag;
  drag.body = lin;
  drag.k1 = 2.0;
  drag.angular = 0.05;
  ASSERT_TRUE(world.addBodyGenerator(drag));
  BodyDrag square;
  square.body = quad;
  square.k2 = 0.5;
  ASSERT_TRUE(world.addBodyGenerator(square));
  for (int step = 0; step < 60; ++step) world.step();
  const Real inertia = 0.4 * 1.0 * 0.25;
  EXPECT_NEAR(world.bodies().angularVelocity(dense(world, lin)).z(),
              2.0 * std::exp(-0.05 / inertia), 0.01 * 2.0 * std::exp(-0.05 / inertia));
  for (int step = 0; step < 1140; ++step) world.step();
  EXPECT_NEAR(world.bodies().linearVelocity(dense(world, lin)).z(), -kG / 2.0, 1e-9);
  EXPECT_NEAR(world.bodies().linearVelocity(dense(world, quad)).z(), -std::sqrt(kG / 0.5), 1e-9);
}

TEST(BodyBuoyancy, ABoxFloatsAtTheDepthItsDensityGives) {
  // A 1 m cube (V = 1 m^3 from its shape) of 500 kg in water: half of it under, its centre at the
  // surface. One of 250 kg by the centre's law with max_depth 0.5: fraction 1/4 = (0.5 - s) / 1,
  // its centre 0.25 m above (the shapes' part would put it at 0.25 m too: a quarter of the cube
  // is under when its centre is 0.25 m up). Drag settles them (awake: a body asleep stops where
  // it was slow, here within a centimetre of its depth).
  World world(config());
  BodySpec half_spec = body(box(Vec3::Constant(0.5)), 500.0, Vec3(0.0, 0.0, 1.0));
  half_spec.can_sleep = false;
  BodySpec quarter_spec = body(box(Vec3::Constant(0.5)), 250.0, Vec3(3.0, 0.0, -1.0));
  quarter_spec.can_sleep = false;
  const BodyId half = *world.addBody(half_spec);
  const BodyId quarter = *world.addBody(quarter_spec);
  BodyBuoyancy floats;
  floats.body = half;
  ASSERT_TRUE(world.addBodyGenerator(floats));
  const BodyBuoyancy& added = world.bodyGenerators().of<BodyBuoyancy>().back();
  EXPECT_EQ(added.model, BuoyancyModel::kShapes);
  EXPECT_NEAR(added.volume, 1.0, 1e-12);
  floats.body = quarter;
  floats.model = BuoyancyModel::kCentre;
  floats.max_depth = 0.5;
  ASSERT_TRUE(world.addBodyGenerator(floats));
  floats.max_depth = -1.0;
  ASSERT_TRUE(world.addBodyGenerator(floats));  // the reach unless given
  EXPECT_NEAR(world.bodyGenerators().of<BodyBuoyancy>().back().max_depth,
              world.bodies().reach(dense(world, quarter)), 1e-12);
  ASSERT_TRUE(world.removeGenerator(world.bodyGenerators().of<BodyBuoyancy>().back().id));
  for (const BodyId id : {half, quarter}) {
    BodyDrag drag;
    drag.body = id;
    drag.k1 = 2000.0;
    ASSERT_TRUE(world.addBodyGenerator(drag));
  }
  for (int step = 0; step < 1200; ++step) world.step();
  EXPECT_NEAR(world.bodies().position(dense(world, half)).z(), 0.0, 1e-3);
  EXPECT_NEAR(world.bodies().position(dense(world, quarter)).z(), 0.25, 1e-3);
}

// A body of the given shape, mass and turn, awake throughout, floating in water below z = 0 by
// the given model, with linear and angular drag to settle it; its state after `seconds`.
struct Floated {
  Vec3 position;
  Quat orientation;
};
Floated floatFor(const BodyShapeSpec& shape, const Real mass, const Quat& turn,
                 const BuoyancyModel model, const Real k1, const Real angular, const Real seconds) {
  World world(config());
  BodySpec spec = body(shape, mass, Vec3::Zero(), turn);
  spec.can_sleep = false;
  const BodyId id = *world.addBody(spec);
  BodyBuoyancy buoyancy;
  buoyancy.body = id;
  buoyancy.model = model;
  EXPECT_TRUE(world.addBodyGenerator(buoyancy));
  BodyDrag drag;
  drag.body = id;
  drag.k1 = k1;
  drag.angular = angular;
  EXPECT_TRUE(world.addBodyGenerator(drag));
  const int steps = static_cast<int>(std::lround(seconds * 60.0));
  for (int step = 0; step < steps; ++step) world.step();
  const std::size_t i = dense(world, id);
  return Floated{world.bodies().position(i), world.bodies().orientation(i)};
}

Real degrees(const Real radians) { return radians * 180.0 / kPi; }

TEST(BodyBuoyancy, AFloatingPlankRightsItselfAtItsCentreOfBuoyancy) {
  // A 2 x 2 x 0.4 m plank of half the water's density (800 kg), let go at the surface tilted 20
  // degrees: the submerged wedge's centroid lies off the centre of mass on the low side and turns
  // it back (metacentric height 1.57 m); it settles flat, half under, centre at the surface. By
  // the centre's law nothing turns it: it stays at 20 degrees.
  const Quat tilted(Eigen::AngleAxisd(20.0 * kPi / 180.0, Vec3::UnitX()));
  const BodyShapeSpec plank = box(Vec3(1.0, 1.0, 0.2));
  const Floated shapes =
      floatFor(plank, 800.0, tilted, BuoyancyModel::kShapes, 6000.0, 2000.0, 10.0);
  EXPECT_LT(degrees(angleBetween(shapes.orientation * Vec3::UnitZ(), Vec3::UnitZ())), 0.1);
  EXPECT_NEAR(shapes.position.z(), 0.0, 1e-4);
  const Floated centre =
      floatFor(plank, 800.0, tilted, BuoyancyModel::kCentre, 6000.0, 2000.0, 10.0);
  EXPECT_NEAR(degrees(angleBetween(centre.orientation * Vec3::UnitZ(), Vec3::UnitZ())), 20.0, 1e-6);
}

TEST(BodyBuoyancy, ASquareLogOfHalfTheDensityRollsOntoAnEdge) {
  // A 4 x 1 x 1 m log of half the water's density: flat on a face is unstable (metacentric
  // height d/2 + a^2/(12 d) - a/2 = -a/12 with draft d = a/2); on an edge, a diagonal of its
  // square section upright, the lower half of the section is a triangle whose centroid is
  // sqrt(2)/6 = 0.236 m below the centre, against 0.25 m for the half face-down: the centre of
  // mass sits lowest above the centre of buoyancy, so it rolls from 10 to 45 degrees and stays.
  const Quat tilted(Eigen::AngleAxisd(10.0 * kPi / 180.0, Vec3::UnitX()));
  const Floated log = floatFor(box(Vec3(2.0, 0.5, 0.5)), 2000.0, tilted, BuoyancyModel::kShapes,
                               8000.0, 300.0, 20.0);
  const Vec3 side = log.orientation * Vec3::UnitY();
  EXPECT_NEAR(degrees(std::atan2(side.z(), side.y())), 45.0, 0.5);
  EXPECT_NEAR((log.orientation * Vec3::UnitX()).z(), 0.0, 1e-3);  // its length stays level
  EXPECT_NEAR(log.position.z(), 0.0, 1e-3);  // half under: the section's diagonal at the surface
}

TEST(BodyBuoyancy, ABallOfAQuarterTheDensityFloatsAtItsCapsDepth) {
  // A ball of radius r under water by a cap of height d holds pi d^2 (3r - d) / 3 of water; a
  // quarter of its volume when d^3 - 3 r d^2 + r^3 = 0, whose root in (0, 2r) puts the centre
  // r - d = 2 r cos(80 degrees) above the surface (the centre's law: r/2).
  const Real r = 0.5;
  const Real mass = 0.25 * 1000.0 * 4.0 / 3.0 * kPi * r * r * r;
  const Floated ball =
      floatFor(sphere(r), mass, Quat::Identity(), BuoyancyModel::kShapes, 2000.0, 10.0, 10.0);
  EXPECT_NEAR(ball.position.z(), 2.0 * r * std::cos(80.0 * kPi / 180.0), 1e-6);
}

TEST(BodyBuoyancy, ACapsuleLogLiesDownOnTheWater) {
  // A capsule of half the water's density let go with its axis 30 degrees from level: it lies
  // down along the surface, half under (by the centre's law it would keep its slope).
  BodyShapeSpec capsule;
  capsule.geometry = CapsuleShape{0.2, 1.0};
  const Real volume = BodyShapeKind<CapsuleShape>::volume(CapsuleShape{0.2, 1.0});
  const Quat pitched(Eigen::AngleAxisd(60.0 * kPi / 180.0, Vec3::UnitY()));
  const Floated log =
      floatFor(capsule, 500.0 * volume, pitched, BuoyancyModel::kShapes, 3000.0, 100.0, 10.0);
  EXPECT_NEAR(degrees(std::asin((log.orientation * Vec3::UnitZ()).z())), 0.0, 0.1);
  EXPECT_NEAR(log.position.z(), 0.0, 1e-4);
}

TEST(BodyForceGenerators, BadInputIsRefusedAndChangesNothing) {
  World world(config());
  const BodyId a = *world.addBody(body(sphere(0.1), 1.0, Vec3::Zero()));
  BodySpec fixed_spec = body(sphere(0.1), 1.0, Vec3(2.0, 0.0, 0.0));
  fixed_spec.type = BodyType::kFixed;
  const BodyId fixed = *world.addBody(fixed_spec);
  ParticleSpec particle;
  particle.position = Vec3(0.0, 2.0, 0.0);
  const ParticleId p = *world.addParticle(particle);
  const std::uint64_t hash = world.stateHash();
  const auto refused = [&](const PointSpring& spring, const std::string& why) {
    const Result<GeneratorId> added = world.addBodyGenerator(spring);
    EXPECT_FALSE(added) << why;
    if (!added)
      EXPECT_NE(added.status().message().find(why), std::string::npos) << added.status().message();
  };
  refused(PointSpring::between(JointEnd::atParticle(p), JointEnd::inWorld(Vec3::Zero()), 1.0),
          "needs a body");
  refused(PointSpring::between(JointEnd::onBody(a), JointEnd::onBody(a, Vec3::UnitX()), 1.0),
          "same body");
  refused(PointSpring::between(JointEnd::onBody(fixed), JointEnd::inWorld(Vec3::Zero()), 1.0),
          "neither end");
  refused(PointSpring::between(JointEnd::onBody(a), JointEnd::inWorld(Vec3::Zero()), NAN),
          "stiffness");
  refused(
      PointSpring::between(JointEnd::onBody(a), JointEnd::inWorld(Vec3::Zero()), 1.0, 1.0, -1.0),
      "damping");
  refused(PointSpring::between(JointEnd::onBody(a), JointEnd::inWorld(Vec3(INFINITY, 0, 0)), 1.0),
          "not finite");
  refused(PointSpring::between(JointEnd::onBody(BodyId{}), JointEnd::inWorld(Vec3::Zero()), 1.0),
          "a");
  BodyDrag drag;
  drag.body = a;
  drag.k2 = -1.0;
  EXPECT_FALSE(world.addBodyGenerator(drag));
  BodyBuoyancy buoyancy;
  buoyancy.body = a;
  buoyancy.up = Vec3::Zero();
  EXPECT_FALSE(world.addBodyGenerator(buoyancy));
  buoyancy.up = Vec3::UnitZ();
  buoyancy.max_depth = 0.0;
  EXPECT_FALSE(world.addBodyGenerator(buoyancy));
  buoyancy.max_depth = 0.5;  // a depth is the centre's law's, not the shapes'
  const Result<GeneratorId> depth = world.addBodyGenerator(buoyancy);
  ASSERT_FALSE(depth);
  EXPECT_NE(depth.status().message().find("max_depth is for model centre"), std::string::npos);
  buoyancy.max_depth = -1.0;
  buoyancy.model = static_cast<BuoyancyModel>(7);
  const Result<GeneratorId> model = world.addBodyGenerator(buoyancy);
  ASSERT_FALSE(model);
  EXPECT_NE(model.status().message().find("model"), std::string::npos);
  EXPECT_TRUE(world.bodyGenerators().empty());
  EXPECT_EQ(world.stateHash(), hash);
}

TEST(BodyForceGenerators, GoWithTheirBodiesAndParticlesAndShareTheGeneratorIds) {
  World world(config());
  const BodyId a = *world.addBody(body(sphere(0.1), 1.0, Vec3::Zero()));
  const BodyId b = *world.addBody(body(sphere(0.1), 1.0, Vec3(2.0, 0.0, 0.0)));
  ParticleSpec particle;
  particle.position = Vec3(0.0, 2.0, 0.0);
  const ParticleId p = *world.addParticle(particle);
  const ParticleId q = *world.addParticle(particle);
  const GeneratorId particle_spring = *world.addGenerator(Spring::between(p, q, 1.0, 1.0));
  const GeneratorId ab =
      *world.addBodyGenerator(PointSpring::between(JointEnd::onBody(a), JointEnd::onBody(b), 1.0));
  const GeneratorId ap = *world.addBodyGenerator(
      PointSpring::between(JointEnd::onBody(a), JointEnd::atParticle(p), 1.0));
  BodyDrag drag;
  drag.body = b;
  drag.k1 = 1.0;
  const GeneratorId drag_id = *world.addBodyGenerator(drag);
  EXPECT_NE(ab, particle_spring);
  EXPECT_NE(ap, ab);
  EXPECT_EQ(world.bodyGenerators().size(), 3u);
  ASSERT_TRUE(world.removeParticle(p));
  EXPECT_TRUE(world.bodyGenerators().of<PointSpring>().size() == 1u &&
              world.bodyGenerators().of<PointSpring>()[0].id == ab);
  ASSERT_TRUE(world.removeBody(b));
  EXPECT_TRUE(world.bodyGenerators().empty());
  EXPECT_FALSE(world.removeGenerator(drag_id));
  const GeneratorId again = *world.addBodyGenerator(
      PointSpring::between(JointEnd::onBody(a), JointEnd::atParticle(q), 1.0));
  ASSERT_TRUE(world.removeGenerator(again));
  EXPECT_TRUE(world.bodyGenerators().empty());
  world.step();
}

TEST(BodyForceGenerators, JoinedBodiesStayAwakeAndAddingOneWakesItsBody) {
  // A box asleep on the ground wakes when a spring to the world is added and lifts; two boxes
  // resting side by side on the ground, joined by a spring, never sleep (a spring between two
  // bodies is not part of an island), while a lone box beside them does.
  World world(config());
  addGround(world);
  const BodyId lone = *world.addBody(body(box(Vec3::Constant(0.5)), 1.0, Vec3(0.0, 0.0, 0.5)));
  const BodyId a = *world.addBody(body(box(Vec3::Constant(0.5)), 1.0, Vec3(3.0, 0.0, 0.5)));
  const BodyId b = *world.addBody(body(box(Vec3::Constant(0.5)), 1.0, Vec3(4.5, 0.0, 0.5)));
  ASSERT_TRUE(
      world.addBodyGenerator(PointSpring::between(JointEnd::onBody(a), JointEnd::onBody(b), 5.0)));
  for (int step = 0; step < 120; ++step) world.step();
  EXPECT_FALSE(world.bodies().awake(dense(world, lone)));
  EXPECT_TRUE(world.bodies().awake(dense(world, a)));
  EXPECT_TRUE(world.bodies().awake(dense(world, b)));
  // 30 N up against 9.81 N of weight.
  ASSERT_TRUE(world.addBodyGenerator(PointSpring::between(
      JointEnd::onBody(lone), JointEnd::inWorld(Vec3(0.0, 0.0, 10.5)), 3.0, 0.0)));
  EXPECT_TRUE(world.bodies().awake(dense(world, lone)));
  for (int step = 0; step < 30; ++step) world.step();
  EXPECT_GT(world.bodies().position(dense(world, lone)).z(), 0.6);
}

TEST(BodyForceGenerators, CopiesStepInLockstep) {
  World world(config());
  addGround(world);
  const BodyId a = *world.addBody(body(box(Vec3::Constant(0.5)), 1.0, Vec3(0.0, 0.0, 2.0)));
  ParticleSpec particle;
  particle.position = Vec3(0.5, 0.0, 4.0);
  const ParticleId p = *world.addParticle(particle);
  ASSERT_TRUE(world.addBodyGenerator(PointSpring::between(
      JointEnd::onBody(a, Vec3(0.5, 0.5, 0.5)), JointEnd::atParticle(p), 30.0, 1.0, 0.5)));
  BodyDrag drag;
  drag.body = a;
  drag.k1 = 0.5;
  drag.angular = 0.1;
  ASSERT_TRUE(world.addBodyGenerator(drag));
  for (int step = 0; step < 30; ++step) world.step();
  World copy = world;
  for (int step = 0; step < 90; ++step) {
    world.step();
    copy.step();
    ASSERT_EQ(world.stateHash(), copy.stateHash()) << "step " << step;
  }
}

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
