#include "mass_aggregate_sim/node/scene_loader.h"

#include <dirent.h>
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "mass_aggregate_sim/node/node_params.h"
#include "yaml_to_xmlrpc.h"

namespace mass_aggregate_sim {
namespace node {
namespace {

using engine::Vec3;

engine::Result<LoadedScene> load(const std::string& yaml, const SceneOverrides& overrides = {}) {
  return loadScene(test::yamlToXmlRpc(yaml), overrides);
}

// The error must name the key and say why.
void expectError(const std::string& yaml, const std::string& key, const std::string& reason,
                 const SceneOverrides& overrides = {}) {
  const auto loaded = load(yaml, overrides);
  ASSERT_FALSE(loaded.isOk()) << yaml;
  EXPECT_EQ(loaded.message().rfind(key + ": ", 0), 0u) << loaded.message();
  EXPECT_NE(loaded.message().find(reason), std::string::npos) << loaded.message();
}

TEST(SceneLoaderTest, MissingSceneIsEmptyWithDefaults) {
  const auto loaded = loadScene(XmlRpc::XmlRpcValue(), SceneOverrides{});
  ASSERT_TRUE(loaded.isOk()) << loaded.message();
  EXPECT_EQ(loaded.value().world.particles().size(), 0u);
  EXPECT_DOUBLE_EQ(loaded.value().rate, 60.0);
  EXPECT_EQ(loaded.value().world.config().gravity, Vec3(0.0, 0.0, -9.81));
  EXPECT_EQ(loaded.value().world.config().integrator, engine::Integrator::kSemiImplicitEuler);
}

TEST(SceneLoaderTest, ParticleTakesEveryProperty) {
  const auto loaded = load(R"(
name: one
rate: 100
substeps: 4
integrator: rk4
gravity: [0, 0, -20]
particles:
  - {name: ball, position: [1, 2, 3], velocity: [4, 5, 6], acceleration: [0, 1, 0],
     mass: 200, radius: 0.5, damping: 0.99}
  - {position: [0, 0, 0], fixed: true}
)");
  ASSERT_TRUE(loaded.isOk()) << loaded.message();
  const engine::World& world = loaded.value().world;
  EXPECT_EQ(loaded.value().name, "one");
  EXPECT_DOUBLE_EQ(loaded.value().rate, 100.0);
  EXPECT_DOUBLE_EQ(world.config().dt, 0.01);
  EXPECT_EQ(world.config().substeps, 4);
  EXPECT_EQ(world.config().integrator, engine::Integrator::kRk4);
  EXPECT_EQ(world.config().gravity, Vec3(0, 0, -20));
  ASSERT_EQ(world.particles().size(), 2u);
  const auto ball = world.particles().findByName("ball");
  ASSERT_TRUE(ball.has_value());
  const std::size_t i = *world.particles().find(*ball);
  EXPECT_EQ(Vec3(world.particles().positions().col(i)), Vec3(1, 2, 3));
  EXPECT_EQ(Vec3(world.particles().velocities().col(i)), Vec3(4, 5, 6));
  EXPECT_EQ(Vec3(world.particles().accelerations().col(i)), Vec3(0, 1, 0));
  EXPECT_DOUBLE_EQ(world.particles().mass(i), 200.0);
  EXPECT_DOUBLE_EQ(world.particles().radii()[i], 0.5);
  EXPECT_DOUBLE_EQ(world.particles().dampings()[i], 0.99);
  EXPECT_EQ(world.particles().inverseMasses()[1 - i], 0.0);
}

TEST(SceneLoaderTest, StepGivenAsDt) {
  const auto loaded = load("{dt: 0.004}");
  ASSERT_TRUE(loaded.isOk()) << loaded.message();
  EXPECT_DOUBLE_EQ(loaded.value().rate, 250.0);
  EXPECT_DOUBLE_EQ(loaded.value().world.config().dt, 0.004);
  expectError("{dt: 0.01, rate: 100}", "scene", "rate or dt, not both");
  expectError("{dt: 0}", "scene.dt", "must be > 0");
}

TEST(SceneLoaderTest, ConfigTheEngineRefusesStopsTheLoad) {
  // dt = 2 s: every field is a number in its range, but the engine's steps are at most 1 s. The
  // load must fail with the engine's reason, not run the scene at another rate.
  expectError("rate: 0.5", "scene", "dt must be finite and in (0, 1] s");
  expectError("dt: 2.0", "scene", "dt must be finite and in (0, 1] s");
}

TEST(SceneLoaderTest, OverridesWinOverTheScene) {
  SceneOverrides overrides;
  overrides.rate = 250.0;
  overrides.substeps = 2;
  overrides.integrator = "velocity_verlet";
  overrides.gravity = Vec3(0, -1, 0);
  const auto loaded =
      load("{rate: 100, substeps: 4, integrator: rk4, gravity: [0, 0, -20]}", overrides);
  ASSERT_TRUE(loaded.isOk()) << loaded.message();
  EXPECT_DOUBLE_EQ(loaded.value().rate, 250.0);
  EXPECT_DOUBLE_EQ(loaded.value().world.config().dt, 1.0 / 250.0);
  EXPECT_EQ(loaded.value().world.config().substeps, 2);
  EXPECT_EQ(loaded.value().world.config().integrator, engine::Integrator::kVelocityVerlet);
  EXPECT_EQ(loaded.value().world.config().gravity, Vec3(0, -1, 0));
}

TEST(SceneLoaderTest, StartupLineNamesTheParametersThatChangedSomething) {
  SceneOverrides overrides;
  overrides.rate = 1.0;
  overrides.substeps = 4;  // what the scene says: changes nothing
  overrides.integrator = "rk4";
  const auto loaded = load("{rate: 100, substeps: 4}", overrides);
  ASSERT_TRUE(loaded.isOk()) << loaded.message();
  NodeParams params;
  params.paused = true;
  params.publish_rate = 20.0;
  params.frame_id = "world";  // given, but the default
  params.limits.max_steps_per_request = 500;
  params.max_service_steps = 500;  // the default when ~max_steps_per_request is below 1000
  params.given = {"rate",         "substeps", "integrator",           "paused",
                  "publish_rate", "frame_id", "max_steps_per_request"};
  EXPECT_EQ(describeParameters(params, loaded.value()),
            "~rate = 1 (scene: 100), ~integrator = rk4 (default: semi_implicit_euler), "
            "~publish_rate = 20 (default: 30), ~paused = true (default: false), "
            "~max_steps_per_request = 500 (default: 100000)");
  // Not on the parameter server: not named, even when it differs (the scene's own value).
  params.given.clear();
  EXPECT_EQ(describeParameters(params, loaded.value()), "");
}

TEST(SceneLoaderTest, LineIsEvenlySpacedNamedFixedAndLinked) {
  const auto loaded = load(R"(
lines:
  - name: chain
    start: [0, 0, 3]
    end: [3, 0, 3]
    count: 4
    mass: 0.5
    fixed_indices: [0, -1]
    link: {type: spring, stiffness: 150, damping: 0.5}
)");
  ASSERT_TRUE(loaded.isOk()) << loaded.message();
  const engine::World& world = loaded.value().world;
  ASSERT_EQ(world.particles().size(), 4u);
  for (int j = 0; j < 4; ++j) {
    const auto id = world.particles().findByName("chain_" + std::to_string(j));
    ASSERT_TRUE(id.has_value()) << j;
    const std::size_t i = *world.particles().find(*id);
    EXPECT_TRUE(Vec3(world.particles().positions().col(i)).isApprox(Vec3(j, 0, 3))) << j;
    EXPECT_EQ(world.particles().inverseMasses()[i], (j == 0 || j == 3) ? 0.0 : 2.0) << j;
  }
  ASSERT_EQ(world.generators().of<engine::Spring>().size(), 3u);
  // rest_length defaults to the distance at load time: the chain starts unstretched.
  for (const auto& spring : world.generators().of<engine::Spring>()) {
    EXPECT_DOUBLE_EQ(spring.rest_length, 1.0);
    EXPECT_DOUBLE_EQ(spring.stiffness, 150.0);
    EXPECT_DOUBLE_EQ(spring.damping, 0.5);
  }
}

TEST(SceneLoaderTest, BlockHasCountTimesParticlesAndReproducibleJitter) {
  const std::string yaml = R"(
blocks:
  - {origin: [0, 0, 1], count: [3, 4, 5], spacing: 0.5, jitter: 0.01, seed: 7, radius: 0.2}
)";
  const auto first = load(yaml);
  const auto second = load(yaml);
  ASSERT_TRUE(first.isOk()) << first.message();
  ASSERT_EQ(first.value().world.particles().size(), 60u);
  EXPECT_EQ(first.value().world.stateHash(), second.value().world.stateHash());
  const auto x = first.value().world.particles().positions();
  for (std::size_t i = 0; i < 60; ++i) {
    const Vec3 nominal(0.5 * (i % 3), 0.5 * ((i / 3) % 4), 1.0 + 0.5 * (i / 12));
    const Vec3 offset = Vec3(x.col(i)) - nominal;
    EXPECT_LE(offset.cwiseAbs().maxCoeff(), 0.01) << i;
  }
  EXPECT_NE(Vec3(x.col(0)), Vec3(0, 0, 1));  // the jitter did move it
}

TEST(SceneLoaderTest, LinksToParticlesAndAnchors) {
  const auto loaded = load(R"(
particles:
  - {name: a, position: [0, 0, 0]}
  - {name: b, position: [0, 0, 2]}
links:
  - {type: bungee, a: a, b: b, stiffness: 10, rest_length: 1}
  - {type: spring, a: a, anchor: [0, 0, 5], stiffness: 3}
  - {type: stiff_spring, a: b, anchor: [0, 0, 3], stiffness: 1.0e+6, damping: 2}
)");
  ASSERT_TRUE(loaded.isOk()) << loaded.message();
  const auto& g = loaded.value().world.generators();
  // The bungee, then the anchored spring, in the scene's order.
  const auto& springs = g.of<engine::Spring>();
  ASSERT_EQ(springs.size(), 2u);
  EXPECT_TRUE(springs[0].pull_only);
  EXPECT_FALSE(springs[0].anchored());
  EXPECT_DOUBLE_EQ(springs[0].rest_length, 1.0);
  EXPECT_FALSE(springs[1].pull_only);
  EXPECT_TRUE(springs[1].anchored());
  EXPECT_DOUBLE_EQ(springs[1].rest_length, 5.0);
  EXPECT_EQ(springs[1].anchor, Vec3(0, 0, 5));
  ASSERT_EQ(g.of<engine::StiffSpring>().size(), 1u);
  EXPECT_DOUBLE_EQ(g.of<engine::StiffSpring>()[0].stiffness, 1.0e6);
}

TEST(SceneLoaderTest, ForcesApplyToAllMovableOrNamedParticles) {
  const auto loaded = load(R"(
particles:
  - {name: a, position: [0, 0, 0]}
  - {name: b, position: [1, 0, 0]}
  - {name: wall, position: [2, 0, 0], fixed: true}
forces:
  - {type: drag, all: true, k1: 0.1, k2: 0.01}
  - {type: buoyancy, particles: [b], volume: 0.002, max_depth: 0.1}
)");
  ASSERT_TRUE(loaded.isOk()) << loaded.message();
  const auto& g = loaded.value().world.generators();
  EXPECT_EQ(g.of<engine::Drag>().size(), 2u);
  ASSERT_EQ(g.of<engine::Buoyancy>().size(), 1u);
  EXPECT_EQ(g.of<engine::Buoyancy>()[0].particle,
            *loaded.value().world.particles().findByName("b"));
}

TEST(SceneLoaderTest, BadScenesNameTheKeyAndTheReason) {
  expectError("{particles: [{position: [0, 0, 0], mass: 0}]}", "scene.particles[0].mass",
              "must be > 0");
  expectError("{particles: [{position: [0, 0, 0], mass: -1}]}", "scene.particles[0].mass",
              "must be > 0");
  expectError("{particles: [{position: [0, .nan, 0]}]}", "scene.particles[0].position[1]",
              "finite");
  expectError("{particles: [{position: [0, 0]}]}", "scene.particles[0].position", "[x, y, z]");
  expectError("{particles: [{position: [0, 0, 0], masss: 1}]}", "scene.particles[0].masss",
              "unknown key");
  expectError("{particles: [{mass: 1}]}", "scene.particles[0].position", "is required");
  // Checked once, by the engine: the key names the particle, the message the field.
  expectError("{particles: [{position: [0, 0, 0], damping: 1.5}]}", "scene.particles[0]",
              "damping must be in [0, 1]");
  expectError("{particles: [{position: [0, 0, 0], mass: 1.0e6}]}", "scene.particles[0].mass",
              "string '1.0e6' (YAML 1.1 exponents need a dot and a sign: 1.0e+6)");
  expectError("{gravity: [0, 0, .inf]}", "scene.gravity[2]", "finite");
  expectError("{integrator: leapfrog}", "scene.integrator", "unknown integrator 'leapfrog'");
  expectError("{rate: 0}", "scene.rate", "must be in (0, 100000]");
  expectError("{substeps: 0}", "scene.substeps", "[1, 1000]");
  expectError("{particles: {position: [0, 0, 0]}}", "scene.particles", "expected a list");
  expectError("{colour: red}", "scene.colour", "unknown key");
  expectError("{particles: [{name: a, position: [0, 0, 0]}, {name: a, position: [1, 0, 0]}]}",
              "scene.particles[1]", "used twice");
  expectError("{particles: [{name: a, position: [0, 0, 0]}], links: [{type: spring, a: a, b: c}]}",
              "scene.links[0]", "no particle named 'c'");
  expectError("{particles: [{name: a, position: [0, 0, 0]}], links: [{type: rope, a: a, b: a}]}",
              "scene.links[0].type", "unknown link type 'rope'");
  expectError("{particles: [{name: a, position: [0, 0, 0]}], links: [{type: spring, a: a}]}",
              "scene.links[0]", "exactly one of b and anchor");
  expectError("{particles: [{name: a, position: [0, 0, 0]}], links: [{type: spring, a: a, b: a}]}",
              "scene.links[0]", "different particles");
  expectError("{lines: [{name: l, start: [0, 0, 0], end: [1, 0, 0], count: 1}]}",
              "scene.lines[0].count", "at least 2");
  expectError("{lines: [{name: l, start: [0, 0, 0], end: [1, 0, 0], fixed_indices: [5]}]}",
              "scene.lines[0].fixed_indices[0]", "out of range");
  expectError("{blocks: [{count: [2, 0, 2]}]}", "scene.blocks[0].count[1]", ">= 1");
  expectError("{forces: [{type: wind, all: true}]}", "scene.forces[0].type", "unknown force");
  expectError("{forces: [{type: drag, particles: [nobody]}]}", "scene.forces[0].particles[0]",
              "no particle named 'nobody'");
  SceneOverrides small;
  small.max_particles = 10;
  expectError("{blocks: [{count: [3, 3, 3]}]}", "scene.blocks[0].count", "~max_particles", small);
  SceneOverrides bad_rate;
  bad_rate.rate = -5.0;
  expectError("{}", "~rate", "must be in (0, 100000]", bad_rate);
}

std::string readFile(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// Every scene shipped in config/scenes loads.
TEST(SceneLoaderTest, ShippedScenesLoad) {
  const std::string here = __FILE__;
  const std::string dir = here.substr(0, here.rfind("/test/node/")) + "/config/scenes";
  DIR* handle = opendir(dir.c_str());
  ASSERT_NE(handle, nullptr) << dir;
  std::vector<std::string> files;
  while (const dirent* entry = readdir(handle)) {
    const std::string name = entry->d_name;
    if (name.size() > 5 && name.substr(name.size() - 5) == ".yaml") files.push_back(name);
  }
  closedir(handle);
  EXPECT_GE(files.size(), 5u);
  for (const auto& file : files) {
    const auto loaded = load(readFile(dir + "/" + file));
    EXPECT_TRUE(loaded.isOk()) << file << ": " << loaded.message();
    if (loaded.isOk()) {
      const engine::World& world = loaded.value().world;
      EXPECT_GT(world.particles().size() + world.bodies().size(), 0u) << file;
    }
  }
}

TEST(SceneLoaderTest, CollidersCollisionsCablesAndRods) {
  const auto loaded = load(R"(
collisions: {particle_collisions: true, broadphase: uniform_grid, continuous: true,
             particle_restitution: 0.25, particle_friction: 0.5, max_iterations: 12,
             penetration_slop: 0.002, collide_linked: true, max_contacts: 500,
             runaway_speed: 500}
colliders:
  - {type: plane, normal: [0, 0, 2], offset: 0.5, restitution: 0.3, friction: 0.7}
  - {type: sphere, center: [1, 2, 3], radius: 0.5}
  - {type: box, center: [0, 0, 1], half_extents: [1, 2, 3], orientation: [0, 0, 0, 1]}
  - {type: capsule, a: [0, 0, 0], b: [0, 0, 2], radius: 0.25}
particles:
  - {name: a, position: [0, 0, 5]}
  - {name: b, position: [3, 0, 5]}
links:
  - {type: cable, a: a, b: b, max_length: 4, restitution: 0.5}
  - {type: rod, a: a, b: b}
  - {type: cable, a: a, anchor: [0, 0, 7]}
  - {type: rod, a: b, anchor: [3, 0, 6], length: 1.5}
)");
  ASSERT_TRUE(loaded.isOk()) << loaded.message();
  const engine::World& world = loaded.value().world;
  const auto& c = world.collisionSettings();
  EXPECT_TRUE(c.particle_collisions);
  EXPECT_EQ(c.broadphase, engine::Broadphase::kUniformGrid);
  EXPECT_TRUE(c.continuous);
  EXPECT_DOUBLE_EQ(c.particle_restitution, 0.25);
  EXPECT_DOUBLE_EQ(c.particle_friction, 0.5);
  EXPECT_EQ(c.max_iterations, 12);
  EXPECT_DOUBLE_EQ(c.penetration_slop, 0.002);
  EXPECT_TRUE(c.collide_linked);
  EXPECT_EQ(c.max_contacts, 500u);
  EXPECT_EQ(c.runaway_speed, 500.0);
  const auto& colliders = world.colliders();
  ASSERT_EQ(colliders.of<engine::PlaneCollider>().size(), 1u);
  EXPECT_TRUE(colliders.of<engine::PlaneCollider>()[0].normal.isApprox(Vec3::UnitZ()));
  EXPECT_DOUBLE_EQ(colliders.of<engine::PlaneCollider>()[0].material.restitution, 0.3);
  EXPECT_DOUBLE_EQ(colliders.of<engine::PlaneCollider>()[0].material.friction, 0.7);
  ASSERT_EQ(colliders.of<engine::SphereCollider>().size(), 1u);
  EXPECT_EQ(colliders.of<engine::SphereCollider>()[0].center, Vec3(1, 2, 3));
  ASSERT_EQ(colliders.of<engine::BoxCollider>().size(), 1u);
  EXPECT_EQ(colliders.of<engine::BoxCollider>()[0].half_extents, Vec3(1, 2, 3));
  ASSERT_EQ(colliders.of<engine::CapsuleCollider>().size(), 1u);
  EXPECT_DOUBLE_EQ(colliders.of<engine::CapsuleCollider>()[0].radius, 0.25);
  const auto& links = world.links();
  // Each kind in the scene's order: the particle-particle one first, then the anchored one.
  const auto& cables = links.of<engine::Cable>();
  const auto& rods = links.of<engine::Rod>();
  ASSERT_EQ(cables.size(), 2u);
  EXPECT_FALSE(cables[0].anchored());
  EXPECT_DOUBLE_EQ(cables[0].max_length, 4.0);
  EXPECT_DOUBLE_EQ(cables[0].restitution, 0.5);
  ASSERT_EQ(rods.size(), 2u);
  EXPECT_FALSE(rods[0].anchored());
  EXPECT_DOUBLE_EQ(rods[0].length, 3.0);  // the distance at load time
  EXPECT_TRUE(cables[1].anchored());
  EXPECT_DOUBLE_EQ(cables[1].max_length, 2.0);
  EXPECT_TRUE(rods[1].anchored());
  EXPECT_DOUBLE_EQ(rods[1].length, 1.5);
}

TEST(SceneLoaderTest, ACylinderLoadsThroughItsKindsFields) {
  // No node code names the cylinder: the scene reader takes its fields from ShapeKind::fields.
  const auto loaded = load(R"(
colliders:
  - {type: cylinder, center: [1, 2, 3], axis: [0, 0, 2], radius: 0.5, half_height: 0.25,
     friction: 0.4}
)");
  ASSERT_TRUE(loaded.isOk()) << loaded.message();
  const auto& cylinders = loaded.value().world.colliders().of<engine::CylinderCollider>();
  ASSERT_EQ(cylinders.size(), 1u);
  EXPECT_EQ(cylinders[0].center, Vec3(1, 2, 3));
  EXPECT_EQ(cylinders[0].axis, Vec3::UnitZ());
  EXPECT_DOUBLE_EQ(cylinders[0].radius, 0.5);
  EXPECT_DOUBLE_EQ(cylinders[0].half_height, 0.25);
  EXPECT_DOUBLE_EQ(cylinders[0].material.friction, 0.4);
  expectError("colliders: [{type: cylinder, radius: 0.5, heigth: 1}]", "scene.colliders[0].heigth",
              "unknown key");
  expectError("colliders: [{type: cylinder, radius: -1}]", "scene.colliders[0]",
              "cylinder radius must be finite and > 0");
  expectError("colliders: [{type: cone}]", "scene.colliders[0].type",
              "known: plane, sphere, box, capsule, cylinder");
}

TEST(SceneLoaderTest, BadCollidersAndCollisionsNameTheKey) {
  expectError("{colliders: [{type: cone}]}", "scene.colliders[0].type", "unknown collider 'cone'");
  expectError("{colliders: [{type: sphere, radius: -1}]}", "scene.colliders[0]", "radius");
  expectError("{colliders: [{type: plane, normal: [0, 0, 0]}]}", "scene.colliders[0]", "normal");
  expectError("{colliders: [{type: plane, restitution: 2}]}", "scene.colliders[0]", "restitution");
  expectError("{colliders: [{type: box, orientation: [0, 0, 1]}]}",
              "scene.colliders[0].orientation", "[x, y, z, w]");
  expectError("{colliders: [{type: sphere, centre: [0, 0, 0]}]}", "scene.colliders[0].centre",
              "unknown key");
  expectError("{collisions: {broadphase: octree}}", "scene.collisions.broadphase",
              "unknown broadphase 'octree'");
  expectError("{collisions: {max_iterations: 0}}", "scene.collisions", "max_iterations");
  expectError("{collisions: {runaway_speed: 0}}", "scene.collisions",
              "runaway_speed must be finite and > 0");
  expectError("{collisions: {particle_collisions: yes please}}",
              "scene.collisions.particle_collisions", "true or false");
}

}  // namespace
}  // namespace node
}  // namespace mass_aggregate_sim
