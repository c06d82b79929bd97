// Simulation's body and joint requests, without ROS: the analytic answers, all-or-nothing spawns,
// sustained wrenches, and refusals that change nothing.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "mass_aggregate_sim/node/force_field_conversions.h"
#include "mass_aggregate_sim/node/input_limits.h"
#include "mass_aggregate_sim/node/simulation.h"

namespace mass_aggregate_sim {
namespace node {
namespace {

using engine::BodySpec;
using engine::Quat;
using engine::Transform;
using engine::Vec3;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

engine::World emptyScene(const Vec3& gravity = Vec3::Zero()) {
  engine::WorldConfig config;
  config.dt = 0.01;
  config.gravity = gravity;
  engine::World world(config);
  engine::ParticleSpec p;
  p.name = "grain";
  p.position = Vec3(5, 0, 0);
  world.addParticle(p);
  return world;
}

BodySpec cube(const std::string& name, const Vec3& at = Vec3::Zero(), const double mass = 1.0) {
  BodySpec spec;
  spec.name = name;
  spec.pose.position = at;
  spec.mass = mass;
  engine::BodyShapeSpec shape;
  shape.geometry = engine::BoxShape{Vec3::Constant(0.5)};
  spec.shapes.push_back(shape);
  return spec;
}

// The world's state, counts and sustained forces: what a refusal must leave as it was.
struct Fingerprint {
  std::uint64_t hash;
  std::size_t bodies;
  std::size_t joints;
  std::size_t sustained;
  explicit Fingerprint(const Simulation& s)
      : hash(s.world().stateHash()),
        bodies(s.world().bodies().size()),
        joints(s.world().joints().size()),
        sustained(s.sustainedForceCount()) {}
  bool operator==(const Fingerprint& o) const {
    return hash == o.hash && bodies == o.bodies && joints == o.joints && sustained == o.sustained;
  }
};

TEST(SimulationBodiesTest, ImpulseOnAUnitCubeGivesTheAnalyticTwist) {
  Simulation sim(emptyScene(), SimulationLimits{});
  ASSERT_TRUE(sim.spawnBodies({cube("cube")}));
  // J = (0, 1, 0) N s at (0.5, 0, 0): dv = J / m = (0, 1, 0); I = m (1 + 1) / 12 = 1/6, so
  // dw = 6 (r x J) = 6 (0, 0, 0.5) = (0, 0, 3).
  const auto twist =
      sim.applyBodyImpulse({0, "cube"}, Vec3(0, 1, 0), Vec3(0.5, 0, 0), Vec3::Zero());
  ASSERT_TRUE(twist) << twist.message();
  EXPECT_NEAR((twist.value().linear - Vec3(0, 1, 0)).norm(), 0.0, 1e-9);
  EXPECT_NEAR((twist.value().angular - Vec3(0, 0, 3)).norm(), 0.0, 1e-9);
}

TEST(SimulationBodiesTest, TwistIsOfTheFrameOriginNotTheCentreOfMass) {
  Simulation sim(emptyScene(), SimulationLimits{});
  BodySpec spec = cube("offset");
  // The shape 1 m along x of the body's frame: the centre of mass is there.
  spec.shapes[0].local.position = Vec3(1, 0, 0);
  setSpecTwist(spec, Twist{Vec3::Zero(), Vec3(0, 0, 2)});
  // Spinning about z with the origin still: the centre moves at w x (c - o) = (0, 2, 0).
  EXPECT_NEAR((spec.linear_velocity - Vec3(0, 2, 0)).norm(), 0.0, 1e-12);
  const auto ids = sim.spawnBodies({spec});
  ASSERT_TRUE(ids) << ids.message();
  const Twist twist = bodyTwist(sim.world().bodies(), 0);
  EXPECT_NEAR(twist.linear.norm(), 0.0, 1e-12);
  EXPECT_NEAR((twist.angular - Vec3(0, 0, 2)).norm(), 0.0, 1e-12);
}

TEST(SimulationBodiesTest, FramesConvertPosesAndRelativeTwistsBothWays) {
  ReferenceFrame frame;
  frame.pose.position = Vec3(1, 2, 3);
  frame.pose.rotation = Quat(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitZ()));
  frame.twist = Twist{Vec3(0.5, 0, 0), Vec3(0, 0, 1)};
  const Transform local{Vec3(1, 0, 0), Quat::Identity()};
  const Transform world = poseToWorld(frame, local);
  EXPECT_NEAR((world.position - Vec3(1, 3, 3)).norm(), 0.0, 1e-12);
  const Transform back = poseInFrame(frame, world);
  EXPECT_NEAR((back.position - local.position).norm(), 0.0, 1e-12);
  // Still relative to the frame: it moves with the frame's point there, v_f + w_f x (p - o_f).
  const Twist still = twistToWorld(frame, world.position, Twist{});
  EXPECT_NEAR((still.linear - (Vec3(0.5, 0, 0) + Vec3(0, 0, 1).cross(Vec3(0, 1, 0)))).norm(), 0.0,
              1e-12);
  EXPECT_NEAR((still.angular - Vec3(0, 0, 1)).norm(), 0.0, 1e-12);
  const Twist relative{Vec3(1, 0, 0), Vec3(0, 1, 0)};
  const Twist round =
      twistInFrame(frame, world.position, twistToWorld(frame, world.position, relative));
  EXPECT_NEAR((round.linear - relative.linear).norm(), 0.0, 1e-12);
  EXPECT_NEAR((round.angular - relative.angular).norm(), 0.0, 1e-12);
}

TEST(SimulationBodiesTest, SpawnIsAllOrNothingAndNamesAreSharedWithParticles) {
  Simulation sim(emptyScene(), SimulationLimits{});
  const Fingerprint before(sim);
  BodySpec bad = cube("bad");
  bad.shapes[0].geometry = engine::SphereShape{-1.0};
  const auto refused = sim.spawnBodies({cube("good"), bad});
  ASSERT_FALSE(refused);
  EXPECT_EQ(refused.message().rfind("bodies[1].shapes[0].radius: ", 0), 0u) << refused.message();
  EXPECT_TRUE(Fingerprint(sim) == before);
  const auto taken = sim.spawnBodies({cube("grain")});
  ASSERT_FALSE(taken);
  EXPECT_NE(taken.message().find("already taken"), std::string::npos) << taken.message();
  ASSERT_TRUE(sim.spawnBodies({cube("a")}));
  engine::ParticleSpec p;
  p.name = "a";
  EXPECT_FALSE(sim.spawn({p}));  // a particle may not take a body's name either
}

TEST(SimulationBodiesTest, HostileSpecsAreRefusedWithNothingChanged) {
  SimulationLimits limits;
  limits.max_bodies = 4;
  Simulation sim(emptyScene(), limits);
  ASSERT_TRUE(sim.spawnBodies({cube("keep")}));
  const Fingerprint before(sim);
  const auto with = [](auto change) {
    BodySpec spec = cube("x");
    change(spec);
    return spec;
  };
  const std::vector<std::pair<const char*, BodySpec>> hostile = {
      {"NaN position", with([](BodySpec& s) { s.pose.position.x() = kNaN; })},
      {"Inf position", with([](BodySpec& s) { s.pose.position.y() = kInf; })},
      {"beyond 1e6 m", with([](BodySpec& s) { s.pose.position.z() = 1e6 + 1; })},
      {"zero quaternion", with([](BodySpec& s) { s.pose.rotation = Quat(0, 0, 0, 0); })},
      {"non-unit quaternion", with([](BodySpec& s) { s.pose.rotation = Quat(1.00001, 0, 0, 0); })},
      {"NaN quaternion", with([](BodySpec& s) { s.pose.rotation = Quat(kNaN, 0, 0, 0); })},
      {"NaN velocity", with([](BodySpec& s) { s.linear_velocity.x() = kNaN; })},
      {"Inf angular velocity", with([](BodySpec& s) { s.angular_velocity.z() = kInf; })},
      {"too fast", with([](BodySpec& s) { s.linear_velocity.x() = 2e5; })},
      {"spinning too fast", with([](BodySpec& s) { s.angular_velocity.x() = 2e4; })},
      {"zero size",
       with([](BodySpec& s) { s.shapes[0].geometry = engine::BoxShape{Vec3(0.5, 0, 0.5)}; })},
      {"negative size",
       with([](BodySpec& s) { s.shapes[0].geometry = engine::SphereShape{-0.1}; })},
      {"NaN size", with([](BodySpec& s) {
         s.shapes[0].geometry = engine::CapsuleShape{kNaN, 0.1};
       })},
      {"too large", with([](BodySpec& s) { s.shapes[0].geometry = engine::SphereShape{1001.0}; })},
      {"no shape", with([](BodySpec& s) { s.shapes.clear(); })},
      {"65 shapes", with([](BodySpec& s) { s.shapes.resize(65, s.shapes[0]); })},
      {"shape far away", with([](BodySpec& s) { s.shapes[0].local.position.x() = 2e3; })},
      {"shape zero quaternion",
       with([](BodySpec& s) { s.shapes[0].local.rotation = Quat(0, 0, 0, 0); })},
      {"mass < 0", with([](BodySpec& s) { s.mass = -1.0; })},
      {"mass NaN", with([](BodySpec& s) { s.mass = kNaN; })},
      {"mass too small", with([](BodySpec& s) { s.mass = 1e-7; })},
      {"density 0", with([](BodySpec& s) {
         s.mass = 0.0;
         s.shapes[0].density = 0.0;
       })},
      {"density mass too small", with([](BodySpec& s) {
         s.mass = 0.0;
         s.shapes[0].density = 1e-3;
         s.shapes[0].geometry = engine::SphereShape{0.001};
       })},
      {"singular inertia",
       with([](BodySpec& s) { s.shapes[0].geometry = engine::BoxShape{Vec3(1e3, 1e-4, 1e-4)}; })},
      {"friction < 0", with([](BodySpec& s) { s.shapes[0].material.friction = -0.1; })},
      {"restitution > 1", with([](BodySpec& s) { s.shapes[0].material.restitution = 1.5; })},
      {"negative damping", with([](BodySpec& s) { s.linear_damping = -1.0; })},
      {"fixed with a velocity", with([](BodySpec& s) {
         s.type = engine::BodyType::kFixed;
         s.linear_velocity.x() = 1.0;
       })},
      {"world frame name", with([](BodySpec& s) { s.name = "world"; })},
      {"name with a space", with([](BodySpec& s) { s.name = "a b"; })},
      {"taken name", with([](BodySpec& s) { s.name = "keep"; })},
  };
  for (const auto& [what, spec] : hostile) {
    const auto refused = sim.spawnBodies({spec});
    EXPECT_FALSE(refused) << what;
    EXPECT_FALSE(refused.message().empty()) << what;
    EXPECT_TRUE(Fingerprint(sim) == before) << what;
  }
  EXPECT_FALSE(sim.spawnBodies({}));
  EXPECT_FALSE(sim.spawnBodies(std::vector<BodySpec>(4, cube(""))));  // 1 + 4 > max_bodies 4
  EXPECT_TRUE(Fingerprint(sim) == before);
}

TEST(SimulationBodiesTest, SpawnAtTheLimits) {
  SimulationLimits limits;
  limits.max_bodies = 3;
  Simulation sim(emptyScene(), limits);
  BodySpec far = cube("far", Vec3(1e6, -1e6, 1e6), kMaxMass);
  far.shapes[0].geometry = engine::BoxShape{Vec3::Constant(kMaxBodySize)};
  BodySpec light = cube("light", Vec3(-1e6, 1e6, -1e6), kMinMass);
  light.shapes[0].geometry = engine::SphereShape{kMinBodySize};
  BodySpec fast = cube("fast");
  fast.linear_velocity = Vec3::Constant(kMaxSpeed);
  const auto ids = sim.spawnBodies({far, light, fast});
  ASSERT_TRUE(ids) << ids.message();
  EXPECT_EQ(sim.world().bodies().size(), 3u);
  EXPECT_FALSE(sim.spawnBodies({cube("one_more")}));
}

TEST(SimulationBodiesTest, DurationWrenchLastsRoundTOverDtSteps) {
  Simulation sim(emptyScene(), SimulationLimits{});
  ASSERT_TRUE(sim.spawnBodies({cube("pushed", Vec3::Zero(), 2.0)}));
  WrenchRequest w;
  w.body.name = "pushed";
  w.force = Vec3(3, 0, 0);
  w.mode = ForceMode::kDuration;
  w.duration = 0.25;
  const auto steps = sim.applyBodyWrench(w);
  ASSERT_TRUE(steps) << steps.message();
  EXPECT_EQ(*steps, 25u);
  for (int i = 0; i < 40; ++i) sim.step();
  // F t / m over exactly 25 steps of 0.01 s.
  EXPECT_NEAR(bodyTwist(sim.world().bodies(), 0).linear.x(), 3.0 * 0.25 / 2.0, 1e-12);
  EXPECT_EQ(sim.sustainedForceCount(), 0u);
}

TEST(SimulationBodiesTest, WrenchesCountAgainstTheSustainedLimitAndItsDurationBounds) {
  SimulationLimits limits;
  limits.max_sustained_forces = 2;
  Simulation sim(emptyScene(), limits);
  ASSERT_TRUE(sim.spawnBodies({cube("box")}));
  WrenchRequest w;
  w.body.name = "box";
  w.force = Vec3(1, 0, 0);
  w.mode = ForceMode::kDuration;
  w.duration = 1e12;  // far more steps than a request may span
  const auto too_long = sim.applyBodyWrench(w);
  ASSERT_FALSE(too_long);
  EXPECT_EQ(too_long.message(), "duration is too long");
  w.duration = 0.004;  // under a step: one step
  const auto short_one = sim.applyBodyWrench(w);
  ASSERT_TRUE(short_one) << short_one.message();
  EXPECT_EQ(*short_one, 1u);
  w.mode = ForceMode::kUntilCleared;
  ASSERT_TRUE(sim.applyBodyWrench(w));
  const Fingerprint full(sim);
  const auto third = sim.applyBodyWrench(w);
  ASSERT_FALSE(third);
  EXPECT_EQ(third.message(),
            "mode: already 2 sustained forces and wrenches, the limit (clear some first)");
  EXPECT_TRUE(Fingerprint(sim) == full);
  // A one-step wrench is not kept: the limit does not apply to it.
  w.mode = ForceMode::kOneStep;
  EXPECT_TRUE(sim.applyBodyWrench(w));
  EXPECT_EQ(sim.sustainedForceCount(), 2u);
}

TEST(SimulationBodiesTest, UntilClearedWrenchActsAtTheMaterialPointUntilCleared) {
  Simulation sim(emptyScene(), SimulationLimits{});
  ASSERT_TRUE(sim.spawnBodies({cube("spun")}));
  WrenchRequest w;
  w.body.name = "spun";
  w.force = Vec3(0, 1, 0);
  w.point = Vec3(0.5, 0, 0);
  w.mode = ForceMode::kUntilCleared;
  ASSERT_TRUE(sim.applyBodyWrench(w));
  EXPECT_EQ(sim.sustainedForceCount(), 1u);
  for (int i = 0; i < 10; ++i) sim.step();
  w.mode = ForceMode::kClear;
  ASSERT_TRUE(sim.applyBodyWrench(w));
  EXPECT_FALSE(sim.applyBodyWrench(w));  // nothing left to clear
  const Twist after = bodyTwist(sim.world().bodies(), 0);
  for (int i = 0; i < 10; ++i) sim.step();
  EXPECT_NEAR((bodyTwist(sim.world().bodies(), 0).angular - after.angular).norm(), 0.0, 1e-9);
  // 10 steps of 0.5 N m about z on I = 1/6: w_z = 10 * 0.01 * 3 = 0.3 rad/s (the force's arm
  // turns with the body, so a little less).
  EXPECT_NEAR(after.angular.z(), 0.3, 0.01);
  EXPECT_NEAR(after.linear.y(), 0.1, 1e-9);
}

TEST(SimulationBodiesTest, WrenchAndImpulseRefusalsChangeNothing) {
  Simulation sim(emptyScene(), SimulationLimits{});
  BodySpec fixed = cube("wall");
  fixed.type = engine::BodyType::kFixed;
  ASSERT_TRUE(sim.spawnBodies({cube("box"), fixed}));
  const Fingerprint before(sim);
  WrenchRequest w;
  w.body.name = "box";
  const auto expectRefused = [&](const WrenchRequest& r, const char* what) {
    EXPECT_FALSE(sim.applyBodyWrench(r)) << what;
    EXPECT_TRUE(Fingerprint(sim) == before) << what;
  };
  WrenchRequest r = w;
  r.force.x() = kNaN;
  expectRefused(r, "NaN force");
  r = w;
  r.torque.z() = kInf;
  expectRefused(r, "Inf torque");
  r = w;
  r.point.y() = kNaN;
  expectRefused(r, "NaN point");
  r = w;
  r.mode = ForceMode::kDuration;
  r.duration = -1.0;
  expectRefused(r, "negative duration");
  r = w;
  r.body.name = "wall";
  expectRefused(r, "fixed body");
  r = w;
  r.body.name = "ghost";
  expectRefused(r, "unknown body");
  r = w;
  r.mode = ForceMode::kClear;
  expectRefused(r, "nothing to clear");
  EXPECT_FALSE(sim.applyBodyImpulse({0, "wall"}, Vec3(1, 0, 0), Vec3::Zero(), Vec3::Zero()));
  EXPECT_FALSE(sim.applyBodyImpulse({0, "box"}, Vec3(kNaN, 0, 0), Vec3::Zero(), Vec3::Zero()));
  EXPECT_FALSE(sim.applyBodyImpulse({0, "box"}, Vec3(1e6, 0, 0), Vec3::Zero(), Vec3::Zero()));
  EXPECT_FALSE(sim.applyBodyImpulse({0, "box"}, Vec3::Zero(), Vec3::Zero(), Vec3(1e9, 0, 0)));
  EXPECT_FALSE(sim.setBodyState({0, "box"}, Transform{Vec3::Zero(), Quat(0, 0, 0, 0)}, {}));
  EXPECT_FALSE(sim.setBodyState({0, "wall"}, {}, Twist{Vec3(1, 0, 0), Vec3::Zero()}));
  EXPECT_FALSE(sim.setBodyState({0, "box"}, {}, {}));
  EXPECT_TRUE(Fingerprint(sim) == before);
}

TEST(SimulationBodiesTest, SetStateTeleportsAndResetRestoresTheSceneWithZeroVelocity) {
  engine::World scene = emptyScene();
  ASSERT_TRUE(scene.addBody(cube("box", Vec3(0, 0, 1))));
  Simulation sim(scene, SimulationLimits{});
  const std::uint64_t start = sim.world().stateHash();
  const Transform pose{Vec3(3, 0, 1), Quat(Eigen::AngleAxisd(0.5, Vec3::UnitZ()))};
  ASSERT_TRUE(sim.setBodyState({0, "box"}, pose, Twist{Vec3(1, 0, 0), Vec3(0, 0, 2)}));
  const Transform now = sim.world().bodies().pose(0);
  EXPECT_NEAR((now.position - pose.position).norm(), 0.0, 1e-12);
  EXPECT_NEAR(bodyTwist(sim.world().bodies(), 0).linear.x(), 1.0, 1e-12);
  WrenchRequest w;
  w.body.name = "box";
  w.force = Vec3(1, 0, 0);
  w.mode = ForceMode::kUntilCleared;
  ASSERT_TRUE(sim.applyBodyWrench(w));
  for (int i = 0; i < 5; ++i) sim.step();
  sim.reset();
  EXPECT_EQ(sim.world().stateHash(), start);
  EXPECT_EQ(sim.sustainedForceCount(), 0u);
  EXPECT_EQ(bodyTwist(sim.world().bodies(), 0).linear, Vec3::Zero());
  EXPECT_EQ(bodyTwist(sim.world().bodies(), 0).angular, Vec3::Zero());
}

TEST(SimulationBodiesTest, RemovingABodyTakesItsJointsWrenchesAndJointNames) {
  Simulation sim(emptyScene(), SimulationLimits{});
  ASSERT_TRUE(sim.spawnBodies({cube("a"), cube("b", Vec3(2, 0, 0))}));
  JointRequest hinge;
  hinge.type = "hinge";
  hinge.name = "elbow";
  hinge.a = {JointEndRef::Kind::kBody, 0, "a"};
  hinge.b = {JointEndRef::Kind::kBody, 0, "b"};
  hinge.anchor_a = hinge.anchor_b = Vec3(1, 0, 0);
  hinge.values.directions["axis"] = Vec3(0, 1, 0);
  const auto id = sim.addJoint(hinge);
  ASSERT_TRUE(id) << id.message();
  EXPECT_EQ(jointName(sim.jointNames(), *id), "elbow");
  EXPECT_EQ(findJoint(sim.world(), sim.jointNames(), "elbow"), *id);
  WrenchRequest w;
  w.body.name = "b";
  w.mode = ForceMode::kUntilCleared;
  ASSERT_TRUE(sim.applyBodyWrench(w));
  const auto removed = sim.removeBodies({{0, "b"}});
  ASSERT_TRUE(removed) << removed.message();
  EXPECT_EQ(removed.value().joints, 1u);
  EXPECT_EQ(sim.world().joints().size(), 0u);
  EXPECT_EQ(sim.sustainedForceCount(), 0u);
  EXPECT_TRUE(sim.jointNames().empty());
  EXPECT_FALSE(sim.removeBodies({{0, "b"}}));
  EXPECT_FALSE(sim.removeBodies({{0, "a"}, {0, "a"}}));  // named twice
  EXPECT_FALSE(sim.removeBodies({}));
}

TEST(SimulationBodiesTest, HostileJointsAreRefusedWithNothingChanged) {
  SimulationLimits limits;
  limits.max_joints = 1;
  Simulation sim(emptyScene(), limits);
  BodySpec wall = cube("wall", Vec3(0, 0, 5));
  wall.type = engine::BodyType::kFixed;
  ASSERT_TRUE(sim.spawnBodies({cube("a"), cube("b", Vec3(2, 0, 0)), wall}));
  JointRequest good;
  good.type = "hinge";
  good.a = {JointEndRef::Kind::kBody, 0, "a"};
  good.b = {JointEndRef::Kind::kBody, 0, "b"};
  good.anchor_a = good.anchor_b = Vec3(1, 0, 0);
  good.values.directions["axis"] = Vec3(0, 0, 1);
  const Fingerprint before(sim);
  const auto with = [&](auto change) {
    JointRequest r = good;
    change(r);
    return r;
  };
  const std::vector<std::pair<const char*, JointRequest>> hostile = {
      {"unknown type", with([](JointRequest& r) { r.type = "slider"; })},
      {"unknown body", with([](JointRequest& r) { r.b.name = "ghost"; })},
      {"unknown id", with([](JointRequest& r) {
         r.b.name.clear();
         r.b.id = 987654321;
       })},
      {"identical bodies", with([](JointRequest& r) { r.b.name = "a"; })},
      {"two world ends", with([](JointRequest& r) {
         r.a = {};
         r.b = {};
       })},
      {"fixed to the world", with([](JointRequest& r) {
         r.a.name = "wall";
         r.b = {};
       })},
      {"hinge to a particle", with([](JointRequest& r) {
         r.b = {JointEndRef::Kind::kParticle, 0, "grain"};
       })},
      {"zero axis", with([](JointRequest& r) { r.values.directions["axis"] = Vec3::Zero(); })},
      {"NaN axis", with([](JointRequest& r) { r.values.directions["axis"] = Vec3(kNaN, 0, 1); })},
      {"lower > upper", with([](JointRequest& r) {
         r.values.flags["limit"] = true;
         r.values.numbers["lower"] = 1.0;
         r.values.numbers["upper"] = -1.0;
       })},
      {"limit beyond pi", with([](JointRequest& r) { r.values.numbers["upper"] = 4.0; })},
      {"NaN motor speed", with([](JointRequest& r) { r.values.numbers["motor_speed"] = kNaN; })},
      {"negative motor torque",
       with([](JointRequest& r) { r.values.numbers["max_motor_torque"] = -1.0; })},
      {"NaN anchor", with([](JointRequest& r) { r.anchor_a.x() = kNaN; })},
      {"anchor beyond 1e6", with([](JointRequest& r) { r.anchor_b.z() = 2e6; })},
      {"reserved name", with([](JointRequest& r) { r.name = "joint_3"; })},
      {"name with a space", with([](JointRequest& r) { r.name = "my joint"; })},
      {"field missing from a request", with([](JointRequest& r) { r.every_field = true; })},
      {"distance min > max", with([](JointRequest& r) {
         r.type = "distance";
         r.values.numbers["min_length"] = 2.0;
         r.values.numbers["max_length"] = 1.0;
       })},
      {"distance Inf", with([](JointRequest& r) {
         r.type = "distance";
         r.values.numbers["max_length"] = kInf;
       })},
  };
  for (const auto& [what, request] : hostile) {
    const auto refused = sim.addJoint(request);
    EXPECT_FALSE(refused) << what;
    EXPECT_FALSE(refused.message().empty()) << what;
    EXPECT_TRUE(Fingerprint(sim) == before) << what << ": " << refused.message();
  }
  ASSERT_TRUE(sim.addJoint(good));
  EXPECT_FALSE(sim.addJoint(good));  // ~max_joints 1
  EXPECT_FALSE(sim.removeJoint(12345));
  EXPECT_FALSE(sim.setHingeMotor(12345, true, 1.0, 1.0));
  EXPECT_FALSE(sim.setHingeMotor(1, true, kNaN, 1.0));
  EXPECT_FALSE(sim.setHingeMotor(1, true, 1.0, -1.0));
}

TEST(SimulationBodiesTest, EveryJointKindJoinsBodiesParticlesAndTheWorld) {
  Simulation sim(emptyScene(Vec3(0, 0, -9.81)), SimulationLimits{});
  ASSERT_TRUE(sim.spawnBodies({cube("a"), cube("b", Vec3(2, 0, 0)), cube("c", Vec3(4, 0, 0))}));
  const auto body = [](const char* name) { return JointEndRef{JointEndRef::Kind::kBody, 0, name}; };
  JointRequest ball;
  ball.type = "ball";
  ball.a = body("a");
  ball.anchor_a = ball.anchor_b = Vec3(0, 0, 1);
  JointRequest fixed;
  fixed.type = "fixed";
  fixed.a = body("a");
  fixed.b = body("b");
  fixed.anchor_a = fixed.anchor_b = Vec3(1, 0, 0);
  JointRequest rod;
  rod.type = "distance";
  rod.a = body("c");
  rod.b = {JointEndRef::Kind::kParticle, 0, "grain"};
  rod.anchor_a = rod.anchor_b = Vec3(4, 0, 0);
  rod.values.numbers["min_length"] = -1.0;
  rod.values.numbers["max_length"] = -1.0;
  for (const JointRequest* r : {&ball, &fixed, &rod}) {
    const auto id = sim.addJoint(*r);
    EXPECT_TRUE(id) << r->type << ": " << id.message();
  }
  EXPECT_EQ(sim.world().joints().size(), 3u);
  for (int i = 0; i < 50; ++i) sim.step();
  EXPECT_TRUE(sim.world().bodies().pose(0).position.allFinite());
  // Removing the particle takes its joint.
  ASSERT_TRUE(sim.remove({ParticleRef{0, "grain"}}));
  EXPECT_EQ(sim.world().joints().size(), 2u);
}

TEST(SimulationBodiesTest, MotorChangesAtRuntimeAndNamedLookups) {
  Simulation sim(emptyScene(), SimulationLimits{});
  ASSERT_TRUE(sim.spawnBodies({cube("wheel")}));
  JointRequest hinge;
  hinge.type = "hinge";
  // The motor turns b relative to a: the wheel relative to the world.
  hinge.b = {JointEndRef::Kind::kBody, 0, "wheel"};
  hinge.anchor_a = hinge.anchor_b = Vec3::Zero();
  hinge.values.directions["axis"] = Vec3(0, 0, 1);
  const auto id = sim.addJoint(hinge);
  ASSERT_TRUE(id) << id.message();
  EXPECT_EQ(jointName(sim.jointNames(), *id), "joint_" + std::to_string(*id));
  EXPECT_EQ(findJoint(sim.world(), sim.jointNames(), "joint_" + std::to_string(*id)), *id);
  EXPECT_FALSE(findJoint(sim.world(), sim.jointNames(), "joint_999"));
  ASSERT_TRUE(sim.setHingeMotor(*id, true, 2.0, 100.0));
  for (int i = 0; i < 100; ++i) sim.step();
  EXPECT_NEAR(sim.world().bodies().angularVelocity(0).z(), 2.0, 1e-3);
  ASSERT_TRUE(sim.removeJoint(*id));
  EXPECT_FALSE(sim.removeJoint(*id));
}

}  // namespace
}  // namespace node
}  // namespace mass_aggregate_sim

namespace mass_aggregate_sim {
namespace node {
namespace {

// ~add_body_spring's requests: a spring held where asked (a body keeps its point in its own frame,
// a negative rest length is the distance now), a bungee to a particle, every hostile request
// refused with the world unchanged, ~max_links counting them with the links, ~remove_link
// removing them.
TEST(SimulationBodiesTest, BodySpringsAreAddedRefusedCountedAndRemoved) {
  SimulationLimits limits;
  limits.max_links = 2;
  Simulation sim(emptyScene(), limits);
  ASSERT_TRUE(sim.spawnBodies({cube("crate", Vec3(0, 0, 2))}));
  BodySpringRequest good;
  good.a = JointEndRef{JointEndRef::Kind::kBody, 0, "crate"};
  good.b = JointEndRef{};  // the world
  good.anchor_a = Vec3(0.5, 0, 2.5);
  good.anchor_b = Vec3(0.5, 0, 4);
  good.stiffness = 50.0;
  good.damping = 0.5;

  const auto with = [&](auto change) {
    BodySpringRequest r = good;
    change(r);
    return r;
  };
  const Fingerprint before(sim);
  const std::size_t generators = sim.world().bodyGenerators().size();
  const std::vector<std::pair<std::string, BodySpringRequest>> hostile = {
      {"two particles", with([](BodySpringRequest& r) {
         r.a = {JointEndRef::Kind::kParticle, 0, "grain"};
         r.b = {JointEndRef::Kind::kParticle, 0, "grain"};
       })},
      {"world to world", with([](BodySpringRequest& r) { r.a = {}; })},
      {"unknown body", with([](BodySpringRequest& r) { r.a.name = "nobody"; })},
      {"unknown particle", with([](BodySpringRequest& r) {
         r.b = {JointEndRef::Kind::kParticle, 0, "nothing"};
       })},
      {"negative stiffness", with([](BodySpringRequest& r) { r.stiffness = -1.0; })},
      {"stiffness beyond 1e12", with([](BodySpringRequest& r) { r.stiffness = 2e12; })},
      {"NaN damping", with([](BodySpringRequest& r) { r.damping = kNaN; })},
      {"infinite rest length", with([](BodySpringRequest& r) { r.rest_length = kInf; })},
      {"rest length beyond 4e6", with([](BodySpringRequest& r) { r.rest_length = 5e6; })},
      {"NaN anchor", with([](BodySpringRequest& r) { r.anchor_a.y() = kNaN; })},
      {"world anchor beyond 1e6", with([](BodySpringRequest& r) { r.anchor_b.x() = 2e6; })},
  };
  for (const auto& [what, request] : hostile) {
    const auto refused = sim.addBodySpring(request);
    EXPECT_FALSE(refused) << what;
    EXPECT_FALSE(refused.message().empty()) << what;
    EXPECT_TRUE(Fingerprint(sim) == before) << what << ": " << refused.message();
    EXPECT_EQ(sim.world().bodyGenerators().size(), generators) << what;
  }
  EXPECT_FALSE(parseBodySpringType("coil"));
  EXPECT_NE(parseBodySpringType("coil").message().find("spring, bungee"), std::string::npos);

  const auto spring = sim.addBodySpring(good);
  ASSERT_TRUE(spring) << spring.message();
  const auto& springs = sim.world().bodyGenerators().of<engine::PointSpring>();
  ASSERT_EQ(springs.size(), 1u);
  EXPECT_TRUE(springs[0].a.isBody());
  EXPECT_TRUE(springs[0].b.isWorld());
  EXPECT_NEAR((springs[0].a.point - Vec3(0.5, 0, 0.5)).norm(), 0.0, 1e-12);  // the body's frame
  EXPECT_NEAR(springs[0].rest_length, 1.5, 1e-12);                           // the distance now
  EXPECT_FALSE(springs[0].pull_only);

  BodySpringRequest bungee = good;
  bungee.pull_only = true;
  bungee.b = JointEndRef{JointEndRef::Kind::kParticle, 0, "grain"};
  bungee.rest_length = 2.0;
  const auto second = sim.addBodySpring(bungee);
  ASSERT_TRUE(second) << second.message();
  EXPECT_TRUE(sim.world().bodyGenerators().of<engine::PointSpring>()[1].pull_only);
  const auto third = sim.addBodySpring(good);  // ~max_links 2
  ASSERT_FALSE(third);
  EXPECT_NE(third.message().find("~max_links"), std::string::npos) << third.message();

  ASSERT_TRUE(sim.removeLink(*spring));
  ASSERT_TRUE(sim.removeLink(*second));
  EXPECT_TRUE(sim.world().bodyGenerators().empty());
}

// ~add_force_field's requests: drag and buoyancy on particles and bodies, all or none (a bad
// target or value anywhere in the request adds nothing), ~max_links counting each, the surface
// placed from the request's frame into the world, ~remove_force_field removing only these.
TEST(SimulationBodiesTest, ForceFieldsAreAddedAllOrNothingCountedAndRemoved) {
  SimulationLimits limits;
  limits.max_links = 4;
  Simulation sim(emptyScene(Vec3(0, 0, -9.81)), limits);
  BodySpec raft_spec = cube("raft", Vec3(0, 0, 0.3), 500.0);
  raft_spec.can_sleep = false;  // asleep, it would stop within a centimetre of its depth
  ASSERT_TRUE(sim.spawnBodies({raft_spec, cube("crate", Vec3(5, 0, 5))}));
  ForceFieldRequest buoyancy;
  buoyancy.type = ForceFieldType::kBuoyancy;
  buoyancy.bodies = {BodyRef{0, "raft"}};
  buoyancy.liquid_density = 1000.0;
  const auto with = [&](auto change) {
    ForceFieldRequest r = buoyancy;
    change(r);
    return r;
  };
  const Fingerprint before(sim);
  const std::vector<std::pair<std::string, ForceFieldRequest>> hostile = {
      {"no target", with([](ForceFieldRequest& r) { r.bodies.clear(); })},
      {"unknown body after a good one", with([](ForceFieldRequest& r) {
         r.bodies.push_back(BodyRef{0, "nobody"});
       })},
      {"unknown particle", with([](ForceFieldRequest& r) {
         r.particles = {{0, "sand"}};
       })},
      {"a particle without a depth",  // the particles' law needs max_depth > 0
       with([](ForceFieldRequest& r) {
         r.particles = {{0, "grain"}};
       })},
      {"a depth for the shapes' model", with([](ForceFieldRequest& r) { r.max_depth = 0.2; })},
      {"negative density", with([](ForceFieldRequest& r) { r.liquid_density = -1.0; })},
      {"NaN surface", with([](ForceFieldRequest& r) { r.surface_height = kNaN; })},
      {"NaN depth", with([](ForceFieldRequest& r) { r.max_depth = kNaN; })},
      {"infinite up", with([](ForceFieldRequest& r) { r.up.x() = kInf; })},
      {"negative drag", with([](ForceFieldRequest& r) {
         r.type = ForceFieldType::kDrag;
         r.k1 = -1.0;
       })},
      {"five against ~max_links 4", with([](ForceFieldRequest& r) {
         r.bodies = {{0, "raft"}, {0, "crate"}, {0, "raft"}, {0, "crate"}, {0, "raft"}};
       })},
  };
  for (const auto& [what, request] : hostile) {
    const auto refused = sim.addForceFields(request);
    EXPECT_FALSE(refused) << what;
    EXPECT_FALSE(refused.message().empty()) << what;
    EXPECT_TRUE(Fingerprint(sim) == before) << what << ": " << refused.message();
    EXPECT_TRUE(sim.world().bodyGenerators().empty()) << what;
    EXPECT_EQ(sim.world().generators().size(), 0u) << what;
  }
  EXPECT_NE(sim.addForceFields(hostile[1].second).message().find("bodies[1]: no body named"),
            std::string::npos);
  EXPECT_NE(sim.addForceFields(hostile[10].second).message().find("5 more exceed ~max_links (4)"),
            std::string::npos)
      << sim.addForceFields(hostile[10].second).message();
  EXPECT_FALSE(parseForceFieldType("wind"));
  EXPECT_NE(parseForceFieldType("wind").message().find("drag, buoyancy"), std::string::npos);
  EXPECT_FALSE(parseBuoyancyModel("center"));

  // The surface 0.5 m above the origin of a frame turned upside down about x and raised 1 m: up
  // is -z in the world, the surface the plane z = 0.5 (the liquid above it).
  ReferenceFrame frame;
  frame.pose.position = Vec3(0, 0, 1);
  frame.pose.rotation = Quat(Eigen::AngleAxisd(M_PI, Vec3::UnitX()));
  ForceFieldRequest placed = buoyancy;
  placed.surface_height = 0.5;
  AddForceField::Request msg;
  placeForceFieldRequest(frame, placed, msg);
  EXPECT_NEAR((placed.up - Vec3(0, 0, -1)).norm(), 0.0, 1e-12);
  EXPECT_NEAR(placed.surface_height, -0.5, 1e-12);  // -z . (0, 0, 0.5) = -0.5
  EXPECT_TRUE(msg.frame_id.empty());
  EXPECT_DOUBLE_EQ(msg.surface_height, -0.5);

  const auto floats = sim.addForceFields(buoyancy);
  ASSERT_TRUE(floats) << floats.message();
  ForceFieldRequest drag;
  drag.particles = {{0, "grain"}};
  drag.bodies = {{0, "crate"}};
  drag.k1 = 0.5;
  drag.angular = 0.1;
  const auto drags = sim.addForceFields(drag);
  ASSERT_TRUE(drags) << drags.message();
  ASSERT_EQ((*drags).size(), 2u);
  EXPECT_EQ(sim.world().generators().of<engine::Drag>()[0].id, (*drags)[0]);  // particles first
  EXPECT_EQ(sim.world().bodyGenerators().of<engine::BodyDrag>()[0].id, (*drags)[1]);
  ForceFieldRequest settle;
  settle.bodies = {{0, "raft"}};
  settle.k1 = 3000.0;
  settle.angular = 100.0;
  const auto settles = sim.addForceFields(settle);
  ASSERT_TRUE(settles) << settles.message();
  EXPECT_FALSE(sim.addForceFields(settle));  // ~max_links: 4 taken
  // The 500 kg cube floats half under, its centre at the surface.
  for (int step = 0; step < 500; ++step) sim.step();
  const auto raft = *sim.world().bodies().findByName("raft");
  EXPECT_NEAR(sim.world().bodies().position(*sim.world().bodies().find(raft)).z(), 0.0, 1e-3);

  EXPECT_FALSE(sim.removeForceField(12345));
  EXPECT_NE(sim.removeForceField(12345).message().find("no drag or buoyancy with id 12345"),
            std::string::npos);
  for (const auto id : *floats) ASSERT_TRUE(sim.removeForceField(id));
  for (const auto id : *drags) ASSERT_TRUE(sim.removeForceField(id));
  for (const auto id : *settles) ASSERT_TRUE(sim.removeForceField(id));
  EXPECT_TRUE(sim.world().bodyGenerators().empty());
  EXPECT_EQ(sim.world().generators().size(), 0u);
}

}  // namespace
}  // namespace node
}  // namespace mass_aggregate_sim
