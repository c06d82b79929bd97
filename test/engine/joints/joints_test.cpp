// Joints (issue 14's acceptance tests 10 and 11): a hinged rod's period, its anchor, its energy,
// hinge limits and motor; Newton's cradle on ball joints; fixed and distance joints; a particle
// holding a body.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "../bodies/body_scenes.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

using namespace test_bodies;

// A thin rod 1 m long, 1 kg, hanging from a hinge about y at its top end, turned by `angle` about
// y. Returns the rod; the hinge's world anchor is the origin.
BodyId hangRod(World& world, const Real angle, HingeJoint hinge = HingeJoint{}) {
  const Quat turn(Eigen::AngleAxisd(angle, Vec3::UnitY()));
  const BodyId rod =
      *world.addBody(body(box(Vec3(0.005, 0.005, 0.5)), 1.0, turn * Vec3(0.0, 0.0, -0.5), turn));
  hinge.a = JointEnd::inWorld(Vec3::Zero());
  hinge.b = JointEnd::onBody(rod, Vec3(0.0, 0.0, 0.5));
  hinge.axis = Vec3::UnitY();
  EXPECT_TRUE(world.addJoint(hinge));
  return rod;
}

// A swing's period from the steps at which x crosses zero going down, at 60 Hz (the crossing's
// time by linear interpolation).
class SwingPeriod {
 public:
  explicit SwingPeriod(const Real x) : previous_x_(x) {}
  void add(const int step, const Real x) {
    if (previous_x_ > 0.0 && x <= 0.0) {
      crossings_.push_back((step - 1 + previous_x_ / (previous_x_ - x)) / 60.0);
    }
    previous_x_ = x;
  }
  std::size_t crossings() const { return crossings_.size(); }
  Real period() const {
    return (crossings_.back() - crossings_.front()) / static_cast<Real>(crossings_.size() - 1);
  }

 private:
  Real previous_x_;
  std::vector<Real> crossings_;
};

TEST(HingeJoint, ARodSwingsWithThePendulumsPeriod) {
  World world(config());
  const Real amplitude = 5.0 * M_PI / 180.0;
  const BodyId rod = hangRod(world, amplitude);
  const std::size_t i = *world.bodies().find(rod);
  // The tip's x crosses zero going the same way once per period.
  SwingPeriod swing(world.bodies().position(i).x());
  Real worst_drift = 0.0;
  const Real e0 = world.totalEnergy();
  Real worst_gain = 0.0;
  for (int step = 1; step <= 20 * 60; ++step) {
    world.step();
    swing.add(step, world.bodies().position(i).x());
    const Vec3 anchor = world.bodies().pose(i).apply(Vec3(0.0, 0.0, 0.5));
    worst_drift = std::max(worst_drift, anchor.norm());
    worst_gain = std::max(worst_gain, world.totalEnergy() - e0);
  }
  ASSERT_GE(swing.crossings(), 3u);
  const Real period = swing.period();
  // T = 2 pi sqrt(I / (m g d)), I = m (L^2 + w^2) / 3 about the end (w = 1 cm: negligible),
  // d = L / 2, with the amplitude's correction 1 + theta^2 / 16.
  const Real l = 1.0;
  const Real inertia = (l * l + 0.01 * 0.01) / 3.0;
  const Real exact =
      2.0 * M_PI * std::sqrt(inertia / (kG * 0.5 * l)) * (1.0 + amplitude * amplitude / 16.0);
  std::printf("[ pendulum ] period %.5f s (exact %.5f), anchor drift %.2e m, energy gain %.2e J\n",
              period, exact, worst_drift, worst_gain);
  EXPECT_NEAR(period, exact, 0.005 * exact);
  EXPECT_NEAR(exact, 1.6388, 0.001);
  EXPECT_LT(worst_drift, 1e-3);
  EXPECT_LT(worst_gain, 1e-6);
}

TEST(HingeJoint, LimitsHold) {
  World world(config());
  HingeJoint hinge;
  hinge.limit = true;
  hinge.lower = -0.2;
  hinge.upper = 0.3;
  const BodyId rod = hangRod(world, 0.0, hinge);
  const std::size_t i = *world.bodies().find(rod);
  // Kick it hard both ways: the angle stays within the limits (a little slop while stopping).
  ASSERT_TRUE(world.setBodyVelocity(rod, Vec3(3.0, 0.0, 0.0), Vec3(0.0, -6.0, 0.0)));
  Real lowest = 0.0;
  Real highest = 0.0;
  for (int step = 0; step < 240; ++step) {
    if (step == 120) {
      ASSERT_TRUE(world.setBodyVelocity(rod, Vec3(-3.0, 0.0, 0.0), Vec3(0.0, 6.0, 0.0)));
    }
    world.step();
    // The rod's angle about y: its axis' direction (from the hinge down) turned from -z.
    const Vec3 down = world.bodies().pose(i).rotation * Vec3(0.0, 0.0, -1.0);
    const Real angle = std::atan2(-down.x(), -down.z());
    lowest = std::min(lowest, angle);
    highest = std::max(highest, angle);
  }
  std::printf("[ hinge ] angle range [%.4f, %.4f] for limits [-0.2, 0.3]\n", lowest, highest);
  EXPECT_GT(lowest, -0.2 - 0.02);
  EXPECT_LT(highest, 0.3 + 0.02);
  EXPECT_LT(lowest, -0.15);  // it reached both
  EXPECT_GT(highest, 0.25);
}

TEST(HingeJoint, AMotorReachesItsSpeedWithinItsTorque) {
  World world(config(0.0));
  const BodyId wheel =
      *world.addBody(body(box(Vec3(0.5, 0.5, 0.1)), 2.0, Vec3::Zero()));  // I_z = 1/3 kg m^2
  HingeJoint hinge;
  hinge.a = JointEnd::inWorld(Vec3::Zero());
  hinge.b = JointEnd::onBody(wheel);
  hinge.axis = Vec3::UnitZ();
  hinge.motor = true;
  hinge.motor_speed = 4.0;
  hinge.max_motor_torque = 1.0;
  const JointId joint = *world.addJoint(hinge);
  const std::size_t i = *world.bodies().find(wheel);
  // At 1 N m on I = 1/3, w grows by 3 rad/s^2: 4 rad/s after 1.333 s, not before.
  for (int step = 0; step < 60; ++step) world.step();
  EXPECT_NEAR(world.bodies().angularVelocity(i).z(), 3.0, 0.01);
  for (int step = 0; step < 60; ++step) world.step();
  EXPECT_NEAR(world.bodies().angularVelocity(i).z(), 4.0, 1e-6);
  // The reaction torque is the motor's only while it accelerates; at speed, none is needed.
  EXPECT_LT(world.jointReactions()[0].torque.norm(), 1e-6);
  ASSERT_TRUE(world.setHingeMotor(joint, true, -2.0, 10.0));
  for (int step = 0; step < 60; ++step) world.step();
  EXPECT_NEAR(world.bodies().angularVelocity(i).z(), -2.0, 1e-6);
}

// Five 1 kg balls of radius 0.1 m in a row along x, 1 mm apart, restitution 1, the first moving
// at `speed`; hung on ball joints 1 m below their anchors, or free (no gravity, no joints).
struct Cradle {
  World world;
  std::vector<BodyId> balls;
};

Cradle cradle(const bool hung, const Real speed, const BodySettings& settings = BodySettings{}) {
  Cradle c{World(config(hung ? kG : 0.0)), {}};
  EXPECT_TRUE(c.world.setBodySettings(settings));
  const Real r = 0.1;
  const Real gap = 0.001;
  const Real length = 1.0;
  for (int k = 0; k < 5; ++k) {
    const Real x = k * (2.0 * r + gap);
    const BodyId ball =
        *c.world.addBody(body(sphere(r, Material{1.0, 0.0}), 1.0, Vec3(x, 0.0, -length)));
    if (hung) {
      EXPECT_TRUE(c.world.addJoint(BallJoint{JointEnd::inWorld(Vec3(x, 0.0, 0.0)),
                                             JointEnd::onBody(ball, Vec3(0.0, 0.0, length))}));
    }
    c.balls.push_back(ball);
  }
  EXPECT_TRUE(c.world.setBodyVelocity(c.balls[0], Vec3(speed, 0.0, 0.0), Vec3::Zero()));
  return c;
}

std::vector<Real> speeds(const Cradle& c) {
  std::vector<Real> v;
  for (const BodyId b : c.balls) {
    v.push_back(c.world.bodies().linearVelocity(*c.world.bodies().find(b)).x());
  }
  return v;
}

TEST(BallJoint, NewtonsCradlePassesTheBallAlong) {
  const Real speed = 2.0;  // above the 1 m/s restitution threshold
  Cradle c = cradle(true, speed);
  for (int step = 0; step < 3; ++step) c.world.step();
  const std::vector<Real> v = speeds(c);
  std::printf("[ cradle ] velocities %.4f %.4f %.4f %.4f %.4f\n", v[0], v[1], v[2], v[3], v[4]);
  EXPECT_GE(v[4], 0.95 * speed);
  for (int k = 0; k < 4; ++k) EXPECT_LT(std::abs(v[k]), 0.05 * speed) << "ball " << k;
}

Real momentumX(const Cradle& c) {
  Real p = 0.0;
  for (const BodyId b : c.balls) {
    const std::size_t i = *c.world.bodies().find(b);
    p += c.world.bodies().mass(i) * c.world.bodies().linearVelocity(i).x();
  }
  return p;
}

TEST(BallJoint, NewtonsCradleConservesMomentumAcrossTheImpactWithTheStringsCounted) {
  // The first ball closes the 1 mm gap at 2 m/s after 0.5 ms: every impact happens in the first
  // step. Over that step the balls' x-momentum changes only by what the strings give (gravity is
  // vertical; the contacts' impulses are equal and opposite on equal-mass balls):
  //   sum m dv_x = sum over the ball joints of J_x,
  // J the impulse each joint gave its ball (end b). With one substep per step, the reaction the
  // world reports (the joint's accumulated impulse over the last substep, / h) is the whole
  // step's, J = F h, and the balance must hold to round-off: 1e-9. Run at 60 Hz and at 240 Hz
  // (the default substep's length, 1/240 s).
  // Without the strings' share, 1e-9 cannot hold: each ball joint holds a point 1 m above a
  // sphere's centre, so a hung ball is a rigid pendulum that must turn (w = v / L) to move. The
  // first ball is given v = 2 m/s without that spin, and its joint brings it onto the
  // pendulum's motion with an impulse of up to I / (I + m L^2) m v = 0.004 / 1.004 * 2 =
  // 8.0e-3 N s (the soft joint gives 7.2e-3 N s of it in the first step: measured); the last
  // ball, set moving by a central, torque-free impact, needs the same a substep later, and
  // gravity pulls each displaced ball back with m g x / L. None of it is an error of the
  // impacts, which is what this balance isolates.
  const Real speed = 2.0;
  for (const int hz : {60, 240}) {
    BodySettings settings;
    settings.substeps = 1;
    Cradle c = cradle(true, speed, settings);
    WorldConfig faster = c.world.config();
    faster.dt = 1.0 / hz;
    ASSERT_TRUE(c.world.setConfig(faster));
    const Real h = c.world.config().dt;
    const Real before = momentumX(c);
    c.world.step();
    ASSERT_EQ(c.world.substepsUsed(), 1);
    const Real after = momentumX(c);
    Real pull = 0.0;
    for (const JointReaction& r : c.world.jointReactions()) pull += r.force.x() * h;
    std::printf(
        "[ cradle ] %d Hz, one substep: momentum %.12f -> %.12f, strings gave %.6e N s, "
        "balance %.2e\n",
        hz, before, after, pull, after - before - pull);
    EXPECT_LT(std::abs(after - before - pull), 1e-9) << hz << " Hz";
    EXPECT_GT(std::abs(pull), 1e-4) << hz << " Hz";  // the strings did act: not a trivial balance
    // And the cradle works at these settings too: after 50 ms the last ball has the speed.
    while (c.world.time() < 0.05 - 1e-9) c.world.step();
    const std::vector<Real> v = speeds(c);
    std::printf("[ cradle ] %d Hz, one substep: velocities %.4f %.4f %.4f %.4f %.4f\n", hz, v[0],
                v[1], v[2], v[3], v[4]);
    EXPECT_GE(v[4], 0.95 * speed) << hz << " Hz";
    for (int k = 0; k < 4; ++k) EXPECT_LT(std::abs(v[k]), 0.05 * speed) << "ball " << k;
  }
}

TEST(BallJoint, TheImpactsOfACradleConserveMomentum) {
  // Without the strings' pull (no gravity, no joints) nothing but the impacts acts: momentum
  // to round-off, and the last ball leaves with the speed.
  const Real speed = 2.0;
  Cradle c = cradle(false, speed);
  const Vec3 p0 = c.world.linearMomentum();
  for (int step = 0; step < 3; ++step) c.world.step();
  const std::vector<Real> v = speeds(c);
  EXPECT_LT((c.world.linearMomentum() - p0).norm(), 1e-9);
  EXPECT_GE(v[4], 0.95 * speed);
  for (int k = 0; k < 4; ++k) EXPECT_LT(std::abs(v[k]), 0.05 * speed) << "ball " << k;
}

TEST(FixedJoint, HoldsTwoBodiesAsOne) {
  World world(config());
  const BodyId a = *world.addBody(body(box(Vec3::Constant(0.25)), 1.0, Vec3(0.0, 0.0, 0.0)));
  const BodyId b = *world.addBody(body(box(Vec3::Constant(0.25)), 1.0, Vec3(0.5, 0.0, 0.0)));
  ASSERT_TRUE(
      world.addJoint(FixedJoint{JointEnd::onBody(a), JointEnd::onBody(b, Vec3(-0.5, 0, 0))}));
  ASSERT_TRUE(world.setBodyVelocity(a, Vec3(0.0, 0.0, 2.0), Vec3(0.0, 3.0, 0.0)));
  for (int step = 0; step < 120; ++step) world.step();
  const Transform pa = world.bodies().pose(*world.bodies().find(a));
  const Transform pb = world.bodies().pose(*world.bodies().find(b));
  const Transform relative = pa.inverse() * pb;
  EXPECT_LT((relative.position - Vec3(0.5, 0.0, 0.0)).norm(), 1e-3);
  EXPECT_LT(relative.rotation.angularDistance(Quat::Identity()), 1e-3);
}

// Two boxes hinged edge to edge (they overlap by 1 cm at the hinge), lying on the ground, and a
// particle held by a ball joint inside one of them. How many contacts join the joint's own ends
// after a second, and the widest the hinge opened.
struct JoinedEnds {
  int body_body = 0;
  int body_particle = 0;
  Real widest_gap = 0.0;
};
JoinedEnds joinedEnds(const bool collide_connected) {
  World world(config());
  addGround(world);
  const Vec3 half(0.255, 0.1, 0.1);
  const BodyId a = *world.addBody(body(box(half), 1.0, Vec3(-0.25, 0.0, 0.1)));
  const BodyId b = *world.addBody(body(box(half), 1.0, Vec3(0.25, 0.0, 0.1)));
  HingeJoint hinge;
  hinge.a = JointEnd::onBody(a, Vec3(0.25, 0.0, 0.0));
  hinge.b = JointEnd::onBody(b, Vec3(-0.25, 0.0, 0.0));
  hinge.axis = Vec3::UnitY();
  hinge.collide_connected = collide_connected;
  EXPECT_TRUE(world.addJoint(hinge));
  ParticleSpec spec;
  spec.position = Vec3(0.25, 0.0, 0.15);
  spec.radius = 0.02;
  const ParticleId p = *world.addParticle(spec);
  BallJoint ball;
  ball.a = JointEnd::onBody(b, Vec3(0.0, 0.0, 0.05));
  ball.b = JointEnd::atParticle(p);
  ball.collide_connected = collide_connected;
  EXPECT_TRUE(world.addJoint(ball));
  JoinedEnds ends;
  for (int step = 0; step < 60; ++step) {
    world.step();
    const Transform pa = world.bodies().pose(*world.bodies().find(a));
    const Transform pb = world.bodies().pose(*world.bodies().find(b));
    ends.widest_gap = std::max(
        ends.widest_gap, (pa.apply(Vec3(0.25, 0.0, 0.0)) - pb.apply(Vec3(-0.25, 0.0, 0.0))).norm());
  }
  for (const BodyContactReport& c : world.bodyContacts()) {
    if (c.other == BodyContactReport::Other::kBody) ++ends.body_body;
    if (c.other == BodyContactReport::Other::kParticle) ++ends.body_particle;
  }
  return ends;
}

TEST(JointEnds, DoNotTouchUnlessCollideConnected) {
  const JoinedEnds apart = joinedEnds(false);
  std::printf("[ joint ] hinged boxes on the ground: widest gap %.2e m apart, %.2e m touching\n",
              apart.widest_gap, joinedEnds(true).widest_gap);
  EXPECT_EQ(apart.body_body, 0);
  EXPECT_EQ(apart.body_particle, 0);
  EXPECT_LT(apart.widest_gap, 1e-3);
  const JoinedEnds touching = joinedEnds(true);
  EXPECT_GE(touching.body_body, 1);
  EXPECT_GE(touching.body_particle, 1);
}

TEST(DistanceJoint, ARopeOfParticlesHoldsABox) {
  // A particle held to the world by a rod, the box hanging from the particle by a cable: the
  // box stays 1.5 m below the anchor (rod 1 m, cable 0.5 m), the cable's reaction carries it.
  World world(config());
  ParticleSpec spec;
  spec.position = Vec3(0.0, 0.0, -1.0);
  spec.inverse_mass = 10.0;
  const ParticleId knot = *world.addParticle(spec);
  ASSERT_TRUE(world.addLink(Rod::anchoredAt(knot, Vec3::Zero(), 1.0)));
  const BodyId box_id = *world.addBody(body(box(Vec3::Constant(0.1)), 2.0, Vec3(0.0, 0.0, -1.6)));
  ASSERT_TRUE(world.addJoint(DistanceJoint::cable(
      JointEnd::atParticle(knot), JointEnd::onBody(box_id, Vec3(0.0, 0.0, 0.1)), 0.5)));
  for (int step = 0; step < 300; ++step) world.step();
  const std::size_t i = *world.bodies().find(box_id);
  EXPECT_NEAR(world.bodies().position(i).z(), -1.6, 5e-3);
  ASSERT_EQ(world.jointReactions().size(), 1u);
  // The cable pulls the box up with its weight: the force on end b (the box) is +m g.
  EXPECT_NEAR(world.jointReactions()[0].force.z(), 2.0 * kG, 0.02 * 2.0 * kG);
}

// A particle swinging 5 degrees on a 1 m rod from a fixed body, under each particle integrator.
// Its row saw it where the integrator had already moved it for the substep, a substep ahead of
// the body: in 20 s it lost half the energy of its swing (a third under velocity Verlet and RK4),
// and under position Verlet, whose history kept none of the rows' velocity change but what the
// position took, 63 %.
class ParticlePendulum : public ::testing::TestWithParam<Integrator> {};

TEST_P(ParticlePendulum, KeepsItsEnergyAndPeriod) {
  WorldConfig c = config();
  c.integrator = GetParam();
  World world(c);
  BodySpec fixed = body(sphere(0.01), 1.0, Vec3::Zero());
  fixed.type = BodyType::kFixed;
  const BodyId pivot = *world.addBody(fixed);
  const Real amplitude = 5.0 * M_PI / 180.0;
  ParticleSpec spec;
  spec.position = Vec3(std::sin(amplitude), 0.0, -std::cos(amplitude));
  spec.inverse_mass = 1.0;
  const ParticleId bob = *world.addParticle(spec);
  ASSERT_TRUE(world.addJoint(
      DistanceJoint::rod(JointEnd::onBody(pivot, Vec3::Zero()), JointEnd::atParticle(bob), 1.0)));
  const auto energy = [&] {
    const std::size_t k = *world.particles().find(bob);
    return 0.5 * world.particles().velocities().col(k).squaredNorm() +
           kG * world.particles().positions().col(k).z();
  };
  const Real start = energy();
  SwingPeriod swing(spec.position.x());
  for (int step = 1; step <= 1200; ++step) {
    world.step();
    swing.add(step, world.particles().positions().col(*world.particles().find(bob)).x());
  }
  ASSERT_GE(swing.crossings(), 2u);
  const Real period = swing.period();
  // T = 2 pi sqrt(L / g) (1 + theta^2 / 16 + 11 theta^4 / 3072)
  const Real expected =
      2.0 * M_PI * std::sqrt(1.0 / kG) *
      (1.0 + amplitude * amplitude / 16.0 + 11.0 * std::pow(amplitude, 4) / 3072.0);
  const Real lost = (start - energy()) / (start + kG);  // of the swing's, above the lowest point
  std::printf("[ joint ] particle pendulum: period %.5f s (%.5f), swing energy lost %.3e\n", period,
              expected, lost);
  EXPECT_NEAR(period, expected, 1e-3 * expected);
  EXPECT_LT(std::abs(lost), 0.05);
}

INSTANTIATE_TEST_SUITE_P(AllIntegrators, ParticlePendulum,
                         ::testing::Values(Integrator::kExplicitEuler,
                                           Integrator::kSemiImplicitEuler,
                                           Integrator::kPositionVerlet, Integrator::kVelocityVerlet,
                                           Integrator::kRk4, Integrator::kImplicitEuler));

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
