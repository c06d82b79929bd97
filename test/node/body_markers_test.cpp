// Bodies, joints and contacts on ~markers, and what the body snapshot holds for the publishers.
#include <gtest/gtest.h>

#include <map>

#include "mass_aggregate_sim/node/body_conversions.h"
#include "mass_aggregate_sim/node/markers.h"
#include "mass_aggregate_sim/node/simulation.h"

namespace mass_aggregate_sim {
namespace node {
namespace {

using engine::Quat;
using engine::Vec3;
using visualization_msgs::Marker;

engine::BodyId addBody(engine::World& world, const std::string& name, const Vec3& at,
                       const engine::AnyBodyShape& shape, const Quat& q = Quat::Identity()) {
  engine::BodySpec spec;
  spec.name = name;
  spec.pose = engine::Transform{at, q};
  engine::BodyShapeSpec s;
  s.geometry = shape;
  spec.shapes.push_back(s);
  return *world.addBody(spec);
}

std::vector<Marker> withNamespace(const visualization_msgs::MarkerArray& array,
                                  const std::string& ns, const int action = Marker::ADD) {
  std::vector<Marker> out;
  for (const auto& m : array.markers) {
    if (m.ns == ns && m.action == action) out.push_back(m);
  }
  return out;
}

TEST(BodyMarkersTest, ShapesAreDrawnAsTheirPartsWithTheirOrientation) {
  engine::World world;
  addBody(world, "box", Vec3(0, 0, 1), engine::BoxShape{Vec3(0.5, 0.25, 0.1)});
  addBody(world, "ball", Vec3(2, 0, 1), engine::SphereShape{0.3});
  // A capsule turned so that its axis (local z) lies along world x.
  const Quat turned(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitY()));
  addBody(world, "pill", Vec3(4, 0, 1), engine::CapsuleShape{0.1, 0.4}, turned);
  MarkerBuilder builder("world", 10.0);
  const auto array = builder.build(world, ros::Time(1.0));
  const auto bodies = withNamespace(array, "bodies");
  ASSERT_EQ(bodies.size(), 5u);  // a cube, a sphere, a cylinder and two spheres
  std::map<int, int> types;
  for (const Marker& m : bodies) ++types[m.type];
  EXPECT_EQ(types[Marker::CUBE], 1);
  EXPECT_EQ(types[Marker::SPHERE], 3);
  EXPECT_EQ(types[Marker::CYLINDER], 1);
  for (const Marker& m : bodies) {
    if (m.type == Marker::CUBE) {
      EXPECT_DOUBLE_EQ(m.scale.x, 1.0);
      EXPECT_DOUBLE_EQ(m.scale.y, 0.5);
      EXPECT_DOUBLE_EQ(m.scale.z, 0.2);
    }
    if (m.type == Marker::CYLINDER) {
      EXPECT_NEAR(m.scale.z, 0.8, 1e-12);
      // Its z along world x.
      const Quat q(m.pose.orientation.w, m.pose.orientation.x, m.pose.orientation.y,
                   m.pose.orientation.z);
      EXPECT_NEAR(((q * Vec3::UnitZ()) - Vec3::UnitX()).norm(), 0.0, 1e-9);
    }
    if (m.type == Marker::SPHERE && m.scale.x == 0.2) {
      // The capsule's end spheres sit at x = 4 +- 0.4.
      EXPECT_NEAR(std::abs(m.pose.position.x - 4.0), 0.4, 1e-9);
      EXPECT_NEAR(m.pose.position.z, 1.0, 1e-9);
    }
  }
}

TEST(BodyMarkersTest, SleepingBodiesAreDimmedAndJointsAreLines) {
  engine::WorldConfig config;
  config.dt = 0.01;
  engine::World world(config);
  const auto a = addBody(world, "a", Vec3(0, 0, 1), engine::SphereShape{0.1});
  addBody(world, "b", Vec3(1, 0, 1), engine::SphereShape{0.1});
  engine::BallJoint ball;
  ball.a = engine::JointEnd::onBody(a, Vec3(0, 0, 1));
  ball.b = engine::JointEnd::inWorld(Vec3(0, 0, 2));
  ASSERT_TRUE(world.addJoint(ball));
  // No gravity: b rests and falls asleep, a is held (and still) too.
  for (int i = 0; i < 200; ++i) world.step();
  WorldSnapshot snapshot;
  takeSnapshot(world, snapshot);
  EXPECT_EQ(snapshot.bodies.sleeping_count, 2u);
  EXPECT_EQ(snapshot.bodies.islands, 2u);
  MarkerBuilder builder("world", 10.0);
  const auto array = builder.build(snapshot, world.colliders(), ros::Time(1.0));
  for (const Marker& m : withNamespace(array, "bodies")) {
    const auto awake = bodyColor(engine::BodyType::kDynamic, false);
    EXPECT_LT(m.color.b, awake.b);
  }
  const auto joints = withNamespace(array, "joints");
  ASSERT_EQ(joints.size(), 1u);
  EXPECT_EQ(joints[0].type, Marker::LINE_LIST);
  // The centre of a to its anchor, and the two anchors.
  ASSERT_EQ(joints[0].points.size(), 4u);
  EXPECT_NEAR(joints[0].points[1].z, 2.0, 1e-6);
}

TEST(BodyMarkersTest, RemovedBodiesAreDeletedAndContactLinesAreOptional) {
  engine::WorldConfig config;
  config.dt = 0.01;
  engine::World world(config);
  ASSERT_TRUE(world.addCollider(engine::PlaneCollider{}));
  const auto box = addBody(world, "box", Vec3(0, 0, 0.49), engine::BoxShape{Vec3::Constant(0.5)});
  for (int i = 0; i < 5; ++i) world.step();
  MarkerBuilder plain("world", 10.0);
  const auto first = plain.build(world, ros::Time(1.0));
  EXPECT_EQ(withNamespace(first, "contacts").size(), 0u);
  MarkerBuilder with_contacts("world", 10.0, true);
  const auto lines = withNamespace(with_contacts.build(world, ros::Time(1.0)), "contacts");
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_GE(lines[0].points.size(), 8u);  // a box face on the ground: four points, two ends each
  ASSERT_TRUE(world.removeBody(box));
  const auto second = plain.build(world, ros::Time(2.0));
  EXPECT_EQ(withNamespace(second, "bodies", Marker::DELETE).size(), 1u);
}

TEST(BodySnapshotTest, HingesGiveJointStatesAndContactsTheirForces) {
  engine::WorldConfig config;
  config.dt = 0.01;
  config.gravity = Vec3(0, 0, -9.81);
  engine::World world(config);
  const auto bob = addBody(world, "bob", Vec3(1, 0, 2), engine::SphereShape{0.1});
  engine::HingeJoint hinge;
  hinge.a = engine::JointEnd::onBody(bob, Vec3(-1, 0, 0));
  hinge.b = engine::JointEnd::inWorld(Vec3(0, 0, 2));
  hinge.axis = Vec3(0, 1, 0);
  const auto id = world.addJoint(hinge);
  ASSERT_TRUE(id);
  for (int i = 0; i < 10; ++i) world.step();
  WorldSnapshot snapshot;
  takeSnapshot(world, snapshot, JointNames{{*id, "swing"}});
  ASSERT_EQ(snapshot.bodies.hinges.size(), 1u);
  const HingeState& state = snapshot.bodies.hinges[0];
  EXPECT_EQ(state.name, "swing");
  // b (the world) relative to a (the bob): the bob falls turning +y, so the world turns -y
  // relative to it.
  EXPECT_NE(state.position, 0.0);
  EXPECT_NE(state.velocity, 0.0);
  sensor_msgs::JointState msg;
  fillJointStates(snapshot.bodies, msg);
  ASSERT_EQ(msg.name.size(), 1u);
  EXPECT_EQ(msg.position[0], state.position);
  BodyArray bodies;
  fillBodyArray(snapshot.bodies, snapshot.step, snapshot.time, bodies);
  ASSERT_EQ(bodies.bodies.size(), 1u);
  EXPECT_EQ(bodies.bodies[0].name, "bob");
  EXPECT_EQ(bodies.step, 10u);
}

// ~contacts' forces are the reported impulses over the last step's substep: a cube resting on the
// ground weighs m g there while it is awake (the bodies' 4 substeps) and once it sleeps (the
// world then takes the particles' 1, and the contacts keep their last impulses).
TEST(BodySnapshotTest, ARestingCubesContactForcesAreItsWeightAwakeAndAsleep) {
  engine::WorldConfig config;
  config.dt = 1.0 / 60.0;
  config.gravity = Vec3(0, 0, -9.81);
  engine::World world(config);
  engine::PlaneCollider ground;
  ASSERT_TRUE(world.addCollider(ground));
  const auto cube = addBody(world, "cube", Vec3(0, 0, 0.5), engine::BoxShape{Vec3::Constant(0.5)});
  const std::size_t i = *world.bodies().find(cube);
  const double weight = world.bodies().mass(i) * 9.81;
  const auto contactForce = [&world]() {
    WorldSnapshot snapshot;
    takeSnapshot(world, snapshot, {}, true);
    BodyContactArray msg;
    fillContacts(snapshot.bodies, {}, {}, snapshot.step, snapshot.time, msg);
    double force = 0.0;
    for (const auto& contact : msg.contacts) {
      for (const auto& point : contact.points) force += point.normal_force;
    }
    return force;
  };
  for (int step = 0; step < 10; ++step) world.step();
  ASSERT_TRUE(world.bodies().awake(i));
  EXPECT_EQ(world.substepsUsed(), world.bodySettings().substeps);
  EXPECT_NEAR(contactForce(), weight, 0.01 * weight);
  for (int step = 0; step < 110; ++step) world.step();
  ASSERT_FALSE(world.bodies().awake(i));
  EXPECT_EQ(world.substepsUsed(), 1);
  EXPECT_NEAR(contactForce(), weight, 0.01 * weight);
}

}  // namespace
}  // namespace node
}  // namespace mass_aggregate_sim
