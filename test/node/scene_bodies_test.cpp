// The scene keys bodies, joints and body_solver: every key checked, misspelt ones refused.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "mass_aggregate_sim/node/body_requests.h"
#include "mass_aggregate_sim/node/scene_loader.h"
#include "yaml_to_xmlrpc.h"

namespace mass_aggregate_sim {
namespace node {
namespace {

using engine::Vec3;

engine::Result<LoadedScene> load(const std::string& yaml, const SceneOverrides& overrides = {}) {
  return loadScene(test::yamlToXmlRpc(yaml), overrides);
}

void expectError(const std::string& yaml, const std::string& key, const std::string& reason,
                 const SceneOverrides& overrides = {}) {
  const auto loaded = load(yaml, overrides);
  ASSERT_FALSE(loaded.isOk()) << yaml;
  EXPECT_EQ(loaded.message().rfind(key + ": ", 0), 0u) << loaded.message();
  EXPECT_NE(loaded.message().find(reason), std::string::npos) << loaded.message();
}

TEST(SceneBodiesTest, BodiesTakeEveryPropertyAndEveryShapeKind) {
  const auto loaded = load(R"(
body_solver: {substeps: 8, iterations: 3, sleep: false}
bodies:
  - name: crate
    type: dynamic
    position: [1, 2, 3]
    orientation: [0, 0, 0, 1]
    velocity: [1, 0, 0]
    angular_velocity: [0, 0, 0.5]
    mass: 4
    linear_damping: 0.1
    angular_damping: 0.2
    can_sleep: false
    shapes:
      - {type: box, half_extents: [0.5, 0.25, 0.1], density: 500, friction: 0.7, restitution: 0.1}
      - {type: sphere, radius: 0.2, position: [0, 0, 0.5]}
      - {type: capsule, radius: 0.1, half_length: 0.3, position: [0.5, 0, 0],
         orientation: [0, 0.7071067811865476, 0, 0.7071067811865476]}
  - {name: floor, type: fixed, position: [0, 0, -1], shapes: [{type: box, half_extents: [5, 5, 0.5]}]}
  - {name: lift, type: kinematic, position: [3, 0, 0], velocity: [0, 0, 1],
     shapes: [{type: sphere, radius: 0.5}]}
)");
  ASSERT_TRUE(loaded.isOk()) << loaded.message();
  const engine::World& world = loaded.value().world;
  ASSERT_EQ(world.bodies().size(), 3u);
  EXPECT_EQ(world.bodySettings().substeps, 8);
  EXPECT_FALSE(world.bodySettings().sleep);
  const std::size_t crate = *world.bodies().find(*world.bodies().findByName("crate"));
  EXPECT_DOUBLE_EQ(world.bodies().mass(crate), 4.0);
  EXPECT_EQ(world.bodies().shapesOf(crate).size(), 3u);
  EXPECT_NEAR((world.bodies().pose(crate).position - Vec3(1, 2, 3)).norm(), 0.0, 1e-12);
  // velocity is the frame origin's.
  const Twist twist = bodyTwist(world.bodies(), crate);
  EXPECT_NEAR((twist.linear - Vec3(1, 0, 0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((twist.angular - Vec3(0, 0, 0.5)).norm(), 0.0, 1e-12);
  EXPECT_EQ(world.bodies().type(*world.bodies().find(*world.bodies().findByName("floor"))),
            engine::BodyType::kFixed);
}

TEST(SceneBodiesTest, CountMakesNamedRowsAndJointsJoinBodiesParticlesAndTheWorld) {
  const auto loaded = load(R"(
particles:
  - {name: bead, position: [0, 0, 5]}
bodies:
  - {name: link, count: 3, position: [0, 0, 2], offset: [1, 0, 0],
     shapes: [{type: sphere, radius: 0.1}]}
joints:
  - {type: hinge, name: root, a: link_0, anchor: [0, 0, 3], axis: [0, 1, 0], limit: true,
     lower: -1, upper: 1, motor: true, motor_speed: 0.5, max_motor_torque: 2}
  - {type: ball, a: link_0, b: link_1, anchor: [0.5, 0, 2]}
  - {type: distance, a: link_2, b: bead, anchor: [2, 0, 2], min_length: 0, max_length: -1}
  - {type: fixed, a: link_1, b: link_2, anchor: [1.5, 0, 2], collide_connected: true}
)");
  ASSERT_TRUE(loaded.isOk()) << loaded.message();
  const engine::World& world = loaded.value().world;
  EXPECT_EQ(world.bodies().size(), 3u);
  ASSERT_TRUE(world.bodies().findByName("link_2"));
  EXPECT_EQ(world.joints().size(), 4u);
  const auto& hinge = world.joints().of<engine::HingeJoint>().at(0);
  EXPECT_TRUE(hinge.limit);
  EXPECT_TRUE(hinge.motor);
  EXPECT_DOUBLE_EQ(hinge.motor_speed, 0.5);
  EXPECT_EQ(loaded.value().joint_names.at(hinge.id), "root");
  const auto& rod = world.joints().of<engine::DistanceJoint>().at(0);
  EXPECT_TRUE(rod.b.isParticle());
  EXPECT_NEAR(rod.max_length, std::sqrt(4.0 + 9.0), 1e-12);  // the distance when loaded
}

TEST(SceneBodiesTest, MisspeltAndBadKeysAreRefusedWithTheKey) {
  const std::string shape = "shapes: [{type: sphere, radius: 0.1}]";
  expectError("bodies: [{position: [0, 0, 0], " + shape + ", colour: red}]",
              "scene.bodies[0].colour", "unknown key");
  expectError("bodies: [{position: [0, 0, 0], shapes: [{type: sphere, radius: 0.1, radious: 1}]}]",
              "scene.bodies[0].shapes[0].radious", "unknown key");
  expectError("bodies: [{position: [0, 0, 0], shapes: [{type: box, radius: 0.1}]}]",
              "scene.bodies[0].shapes[0].radius", "unknown key");
  expectError("bodies: [{position: [0, 0, 0], shapes: [{type: cone}]}]",
              "scene.bodies[0].shapes[0].type", "unknown shape 'cone'");
  expectError("bodies: [{position: [0, 0, 0], shapes: []}]", "scene.bodies[0].shapes",
              "at least one shape");
  expectError("bodies: [{" + shape + "}]", "scene.bodies[0].position", "is required");
  expectError("bodies: [{position: [0, 0, 0], type: floating, " + shape + "}]",
              "scene.bodies[0].type", "unknown body type");
  expectError("bodies: [{position: [0, 0, 0], orientation: [0, 0, 0, 0], " + shape + "}]",
              "scene.bodies[0].orientation", "unit quaternion");
  expectError("bodies: [{position: [0, 0, 0], shapes: [{type: sphere, radius: 0}]}]",
              "scene.bodies[0].shapes[0].radius", "must be in");
  expectError("bodies: [{position: [0, 0, 0], mass: -2, " + shape + "}]", "scene.bodies[0].mass",
              "must be in");
  expectError("bodies: [{name: a, position: [0, 0, 0], " + shape +
                  "}, {name: a, position: [1, 0, 0], " + shape + "}]",
              "scene.bodies[1].name", "used twice");
  expectError(
      "particles: [{name: a, position: [0, 0, 5]}]\nbodies: [{name: a, position: [0, 0, 0], " +
          shape + "}]",
      "scene.bodies[0].name", "used twice");
  expectError("bodies: [{count: 2, position: [0, 0, 0], " + shape + "}]", "scene.bodies[0].name",
              "is required with count");
  SceneOverrides few;
  few.max_bodies = 2;
  expectError("bodies: [{name: b, count: 3, position: [0, 0, 0], " + shape + "}]",
              "scene.bodies[0].count", "~max_bodies", few);
  expectError("body_solver: {substep: 2}", "scene.body_solver.substep", "unknown key");
  expectError("body_solver: {substeps: 0}", "scene.body_solver", "substeps");
  const std::string two = "bodies: [{name: a, position: [0, 0, 0], " + shape +
                          "}, {name: b, position: [1, 0, 0], " + shape + "}]\n";
  expectError(two + "joints: [{type: slider, a: a, anchor: [0, 0, 0]}]", "scene.joints[0].type",
              "unknown joint type 'slider'");
  expectError(two + "joints: [{type: ball, a: a, anchor: [0, 0, 0], axis: [0, 1, 0]}]",
              "scene.joints[0].axis", "unknown key");
  expectError(two + "joints: [{type: hinge, a: a, anchor: [0, 0, 0], axes: [0, 1, 0]}]",
              "scene.joints[0].axes", "unknown key");
  expectError(two + "joints: [{type: hinge, a: a, b: ghost, anchor: [0, 0, 0]}]",
              "scene.joints[0].b", "no body or particle named 'ghost'");
  expectError(two + "joints: [{type: hinge, a: a, b: a, anchor: [0, 0, 0]}]", "scene.joints[0]",
              "same body");
  expectError(two + "joints: [{type: hinge, a: a, anchor: [0, 0, 0], axis: [0, 0, 0]}]",
              "scene.joints[0]", "axis");
  expectError(two + "joints: [{type: hinge, a: a, anchor: [0, 0, 0], lower: 1, upper: -1}]",
              "scene.joints[0]", "lower <= upper");
  expectError(two + "joints: [{type: hinge, a: a}]", "scene.joints[0].anchor", "is required");
  expectError(two + "joints: [{type: hinge, name: joint_7, a: a, anchor: [0, 0, 0]}]",
              "scene.joints[0].name", "kept for a joint without a name");
  SceneOverrides one;
  one.max_joints = 1;
  expectError(
      two +
          "joints: [{type: ball, a: a, anchor: [0, 0, 0]}, {type: ball, a: b, anchor: [0, 0, 0]}]",
      "scene.joints[1]", "~max_joints", one);
}

TEST(SceneBodiesTest, ForcesActOnBodiesThroughSpringsBungeesDragAndBuoyancy) {
  const auto loaded = load(R"(
particles:
  - {name: bead, position: [0, 0, 5]}
bodies:
  - {name: crate, position: [0, 0, 2], shapes: [{type: box, half_extents: [0.5, 0.5, 0.5]}]}
  - {name: float, position: [3, 0, 0], mass: 500, shapes: [{type: box, half_extents: [0.5, 0.5, 0.5]}]}
forces:
  - {type: spring, a: crate, anchor: [0.5, 0, 2.5], anchor_b: [0.5, 0, 4], stiffness: 50}
  - {type: bungee, a: bead, b: crate, stiffness: 20, rest_length: 2, damping: 0.5}
  - {type: drag, bodies: [crate, float], k1: 0.5, k2: 0.1, angular: 0.2}
  - {type: buoyancy, bodies: [float], liquid_density: 1000}
  - {type: buoyancy, bodies: [crate], model: centre, max_depth: 0.2, surface_height: -5}
  - {type: drag, particles: [bead], k1: 0.3}
)");
  ASSERT_TRUE(loaded.isOk()) << loaded.message();
  const engine::World& world = loaded.value().world;
  const auto& springs = world.bodyGenerators().of<engine::PointSpring>();
  ASSERT_EQ(springs.size(), 2u);
  EXPECT_TRUE(springs[0].a.isBody());
  EXPECT_TRUE(springs[0].b.isWorld());
  EXPECT_NEAR((springs[0].a.point - Vec3(0.5, 0, 0.5)).norm(), 0.0, 1e-12);  // the body's frame
  EXPECT_NEAR(springs[0].rest_length, 1.5, 1e-12);  // the distance when loaded
  EXPECT_FALSE(springs[0].pull_only);
  EXPECT_TRUE(springs[1].a.isParticle());
  EXPECT_TRUE(springs[1].pull_only);
  EXPECT_DOUBLE_EQ(springs[1].rest_length, 2.0);
  EXPECT_DOUBLE_EQ(springs[1].damping, 0.5);
  ASSERT_EQ(world.bodyGenerators().of<engine::BodyDrag>().size(), 2u);
  EXPECT_DOUBLE_EQ(world.bodyGenerators().of<engine::BodyDrag>()[1].angular, 0.2);
  const auto& buoyancies = world.bodyGenerators().of<engine::BodyBuoyancy>();
  ASSERT_EQ(buoyancies.size(), 2u);
  EXPECT_EQ(buoyancies[0].model, engine::BuoyancyModel::kShapes);
  EXPECT_NEAR(buoyancies[0].volume, 1.0, 1e-12);
  EXPECT_EQ(buoyancies[1].model, engine::BuoyancyModel::kCentre);
  EXPECT_DOUBLE_EQ(buoyancies[1].max_depth, 0.2);
  EXPECT_DOUBLE_EQ(buoyancies[1].surface_height, -5.0);
  EXPECT_EQ(world.generators().of<engine::Drag>().size(), 1u);
  const std::string two =
      "particles: [{name: p, position: [0, 0, 5]}, {name: q, position: [1, 0, 5]}]\n"
      "bodies: [{name: a, position: [0, 0, 0], shapes: [{type: sphere, radius: 0.1}]}]\n";
  expectError(two + "forces: [{type: spring, a: p, b: q, stiffness: 1}]", "scene.forces[0]",
              "needs a body");
  expectError(two + "forces: [{type: spring, a: a, stiffness: 1}]", "scene.forces[0].anchor_b",
              "is required for an end in the world");
  expectError(two + "forces: [{type: spring, a: a, b: p, stiffnes: 1}]", "scene.forces[0].stiffnes",
              "unknown key");
  expectError(two + "forces: [{type: spring, a: nobody, b: p}]", "scene.forces[0].a",
              "no body or particle named 'nobody'");
  expectError(two + "forces: [{type: spring, a: a, b: p, rest_length: -1}]",
              "scene.forces[0].rest_length", "must be >= 0");
  expectError(two + "forces: [{type: drag, bodies: [b], k1: 1}]", "scene.forces[0].bodies[0]",
              "no body named 'b'");
  expectError(two + "forces: [{type: drag, bodies: [a], k1: -1}]", "scene.forces[0]", "k1 and k2");
  expectError(two + "forces: [{type: buoyancy, bodies: [a], particles: [p]}]",
              "scene.forces[0].particles", "unknown key");
  expectError(two + "forces: [{type: buoyancy, bodies: [a], model: center}]",
              "scene.forces[0].model", "unknown model 'center' (known: shapes, centre)");
  expectError(two + "forces: [{type: buoyancy, bodies: [a], max_depth: 0.2}]", "scene.forces[0]",
              "max_depth is for model centre");
  expectError(two + "forces: [{type: buoyancy, particles: [p], model: shapes}]",
              "scene.forces[0].model", "unknown key");
  SceneOverrides few;
  few.max_links = 1;
  expectError(two + "forces: [{type: drag, bodies: [a], k1: 1}, {type: drag, bodies: [a], k1: 1}]",
              "scene.forces[1]", "~max_links", few);
}

}  // namespace
}  // namespace node
}  // namespace mass_aggregate_sim
