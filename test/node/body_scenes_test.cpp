// The shipped body scenes (config/scenes), and the bridge of links, loaded and run: they stay
// finite and do what their description says. Prints the cost of a step ([ scene ] lines).
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "mass_aggregate_sim/node/scene_loader.h"
#include "mass_aggregate_sim/node/snapshot.h"
#include "yaml_to_xmlrpc.h"

namespace mass_aggregate_sim {
namespace node {
namespace {

using engine::Vec3;

engine::World loadShipped(const std::string& name) {
  const std::string here = __FILE__;
  const std::string path =
      here.substr(0, here.rfind("/test/node/")) + "/config/scenes/" + name + ".yaml";
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  const auto loaded = loadScene(test::yamlToXmlRpc(text.str()), SceneOverrides{});
  EXPECT_TRUE(loaded.isOk()) << name << ": " << loaded.message();
  return loaded.isOk() ? loaded.value().world : engine::World();
}

const Vec3& centre(const engine::World& world, const std::string& name) {
  return world.bodies().position(*world.bodies().find(*world.bodies().findByName(name)));
}

// Steps `seconds` of simulated time, checking that every body stays finite; prints the cost.
void run(engine::World& world, const std::string& name, const double seconds) {
  const int steps = static_cast<int>(seconds / world.config().dt + 0.5);
  const auto start = std::chrono::steady_clock::now();
  for (int i = 0; i < steps; ++i) world.step();
  const double cost =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf(
      "[ scene ] %s: %zu bodies, %zu joints, %zu particles: %.3f ms per step over %d steps\n",
      name.c_str(), world.bodies().size(), world.joints().size(), world.particles().size(),
      1e3 * cost / steps, steps);
  EXPECT_EQ(world.divergenceCount(), 0u) << name;
  for (std::size_t i = 0; i < world.bodies().size(); ++i) {
    EXPECT_TRUE(world.bodies().position(i).allFinite()) << name << " body " << i;
  }
}

// Every scene the package ships is within its integrators' limits: springs, drags and springs
// and drags on bodies (World::stabilityReport()), at its own settings.
TEST(BodyScenesTest, EveryShippedSceneIsStableByItsReport) {
  const std::string here = __FILE__;
  const std::filesystem::path scenes = here.substr(0, here.rfind("/test/node/")) + "/config/scenes";
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(scenes)) {
    if (entry.path().extension() != ".yaml") continue;
    const std::string name = entry.path().stem().string();
    const engine::World world = loadShipped(name);
    EXPECT_TRUE(world.stabilityReport().stable) << name << ": " << world.stabilityReport().message;
    ++count;
  }
  EXPECT_GE(count, 16);
}

TEST(BodyScenesTest, TheBoxStackStandsAndSleeps) {
  engine::World world = loadShipped("box_stack");
  run(world, "box_stack", 4.0);
  EXPECT_NEAR(centre(world, "box_9").z(), 4.75, 0.02);
  EXPECT_NEAR(centre(world, "box_9").x(), 0.0, 0.02);
  WorldSnapshot snapshot;
  takeSnapshot(world, snapshot);
  EXPECT_EQ(snapshot.bodies.sleeping_count, 10u);
  EXPECT_EQ(snapshot.bodies.islands, 1u);
}

TEST(BodyScenesTest, ThePyramidStands) {
  engine::World world = loadShipped("pyramid");
  ASSERT_EQ(world.bodies().size(), 210u);
  run(world, "pyramid", 5.0);
  // The top box stays within 2 cm of where it started (9.75 m up, over x = 0).
  EXPECT_NEAR(centre(world, "row19_0").z(), 9.75, 0.02);
  EXPECT_NEAR(centre(world, "row19_0").x(), 0.0, 0.02);
  WorldSnapshot snapshot;
  takeSnapshot(world, snapshot);
  std::printf("[ scene ] pyramid after 5 s: %zu of 210 sleeping, %zu island(s), %zu contacts\n",
              snapshot.bodies.sleeping_count, snapshot.bodies.islands,
              snapshot.bodies.contact_count);
}

TEST(BodyScenesTest, PendulumsSwingOnTheirHinges) {
  for (const char* name : {"pendulum", "double_pendulum"}) {
    engine::World world = loadShipped(name);
    run(world, name, 3.0);
    WorldSnapshot snapshot;
    takeSnapshot(world, snapshot);
    for (const JointView& joint : snapshot.bodies.joints) {
      EXPECT_LT((joint.anchor_a - joint.anchor_b).norm(), 5e-3) << name;
    }
  }
  engine::World world = loadShipped("pendulum");
  run(world, "pendulum", 1.005);  // half a period: at the other side, 30 degrees up
  EXPECT_NEAR(centre(world, "bob").x(), -0.5, 0.01);
}

TEST(BodyScenesTest, NewtonsCradlePassesTheImpulseAlong) {
  engine::World world = loadShipped("newtons_cradle");
  double farthest = 0.0;
  for (int i = 0; i < 240; ++i) {
    world.step();
    farthest = std::max(farthest, centre(world, "ball_3").x());
  }
  std::printf("[ scene ] newtons_cradle: the last ball reached x = %.3f m (rest 0.4)\n", farthest);
  // The last ball swings out (to x = 1.04 m with no loss); the striker stops.
  EXPECT_GT(farthest, 0.8);
}

TEST(BodyScenesTest, TheCapsuleChainHoldsTogether) {
  engine::World world = loadShipped("capsule_chain");
  run(world, "capsule_chain", 3.0);
  WorldSnapshot snapshot;
  takeSnapshot(world, snapshot);
  double worst = 0.0;
  for (const JointView& joint : snapshot.bodies.joints) {
    worst = std::max(worst, (joint.anchor_a - joint.anchor_b).norm());
  }
  std::printf("[ scene ] capsule_chain: widest hinge gap %.2e m\n", worst);
  EXPECT_LT(worst, 0.002);
}

TEST(BodyScenesTest, ParticlesRainOntoTheStack) {
  engine::World world = loadShipped("particle_rain");
  run(world, "particle_rain", 3.0);
  // The stack stands under the grains; the grains stay above the ground.
  EXPECT_GT(centre(world, "top").z(), 1.15);
  const auto& x = world.particles().positions();
  EXPECT_GT(x.row(2).minCoeff(), 0.0);
  EXPECT_TRUE(x.allFinite());
  // And they come to rest: on the sleeping boxes they are the particle solver's, as on the ground
  // (joined to the body solver there, some crept at up to millimetres a second for good).
  run(world, "particle_rain", 6.0);
  double fastest = 0.0;
  for (int step = 0; step < 120; ++step) {
    world.step();
    fastest = std::max(fastest, world.particles().velocities().colwise().norm().maxCoeff());
  }
  std::printf("[ scene ] particle_rain: fastest grain over the tenth second %.2e m/s\n", fastest);
  EXPECT_LT(fastest, 1e-9);
}

// The bridge of rods and cables catches its 20 kg ball and comes to rest on it. Its closed loops
// of links keep the positions stage at its 40 passes: rods and cables are left within about
// 2e-4 of their lengths (the ball's weight), held here to 1e-3.
TEST(BodyScenesTest, TheBridgeCatchesItsBallAndComesToRest) {
  engine::World world = loadShipped("bridge");
  run(world, "bridge", 20.0);
  const auto position = [&](const engine::ParticleId id) -> Vec3 {
    return world.particles().positions().col(*world.particles().find(id));
  };
  double worst = 0.0;  // relative
  for (const engine::Rod& rod : world.links().of<engine::Rod>()) {
    const Vec3 other = rod.anchored() ? rod.anchor : position(rod.b);
    worst = std::max(worst, std::abs((position(rod.a) - other).norm() / rod.length - 1.0));
  }
  for (const engine::Cable& cable : world.links().of<engine::Cable>()) {
    const Vec3 other = cable.anchored() ? cable.anchor : position(cable.b);
    worst = std::max(worst, (position(cable.a) - other).norm() / cable.max_length - 1.0);
  }
  const Vec3 ball = position(*world.particles().findByName("ball"));
  std::printf(
      "[ scene ] bridge after 20 s: kinetic energy %.3e J, ball at z = %.3f m, links within "
      "%.2e of their lengths\n",
      world.kineticEnergy(), ball.z(), worst);
  EXPECT_LT(worst, 1e-3);
  EXPECT_EQ(world.divergenceCount(), 0u);
  EXPECT_LT(world.kineticEnergy(), 1e-3);
  EXPECT_GT(ball.z(), 1.0);  // on the deck (2 m up at its ends), not through it
  EXPECT_LT(ball.z(), 3.0);
}

TEST(BodyScenesTest, TheRopeHoldsTheBox) {
  engine::World world = loadShipped("rope_box");
  // The ball joint's widest opening over the swing, one step at a time (3 s).
  double widest = 0.0;
  WorldSnapshot snapshot;
  for (int step = 0; step < 360; ++step) {
    world.step();
    takeSnapshot(world, snapshot);
    ASSERT_EQ(snapshot.bodies.joints.size(), 1u);
    widest = std::max(
        widest, (snapshot.bodies.joints[0].anchor_a - snapshot.bodies.joints[0].anchor_b).norm());
  }
  const double gap =
      (snapshot.bodies.joints[0].anchor_a - snapshot.bodies.joints[0].anchor_b).norm();
  std::printf("[ scene ] rope_box: ball joint gap %.3e m (widest %.3e m), crate at z = %.3f m\n",
              gap, widest, centre(world, "crate").z());
  EXPECT_EQ(world.divergenceCount(), 0u);
  EXPECT_TRUE(world.particles().positions().allFinite());
  EXPECT_GT(centre(world, "crate").z(), 0.2);
  EXPECT_LT(widest, 0.05);
  EXPECT_LT(gap, 0.02);
}

TEST(BodyScenesTest, TheCrateHangsTheRaftFloatsAndTheBlockSinks) {
  engine::World world = loadShipped("body_forces");
  run(world, "body_forces", 20.0);
  // The spring carries crate and bead: (20 + 1) 9.81 / 400 = 0.515 m beyond its 1.25 m, from the
  // hook at z = 4 to the crate's top face; the crate is 0.5 m tall.
  EXPECT_NEAR(centre(world, "crate").z(), 4.0 - 1.25 - 0.515 - 0.25, 0.01);
  // Half the raft's volume under water: its centre at the surface (asleep within a centimetre).
  EXPECT_NEAR(centre(world, "raft").z(), 0.0, 0.01);
  EXPECT_NEAR(centre(world, "block").z(), -3.0 + 0.25, 0.01);
  // The square log of half the water's density on an edge (its section's diagonal upright), the
  // capsule lying along the surface; both half under, their centres at the surface.
  const auto turn = [&](const char* name) {
    const engine::BodyStore& bodies = world.bodies();
    return bodies.pose(*bodies.find(*bodies.findByName(name))).rotation;
  };
  const Vec3 side = turn("square_log") * Vec3::UnitY();
  std::printf(
      "[ scene ] body_forces: square log rolled %.2f degrees, round log's axis %.3f "
      "degrees from level\n",
      std::atan2(side.z(), side.y()) * 180.0 / M_PI,
      std::asin((turn("round_log") * Vec3::UnitZ()).z()) * 180.0 / M_PI);
  EXPECT_NEAR(std::atan2(side.z(), side.y()) * 180.0 / M_PI, 45.0, 1.0);
  EXPECT_NEAR(std::asin((turn("round_log") * Vec3::UnitZ()).z()) * 180.0 / M_PI, 0.0, 1.0);
  EXPECT_NEAR(centre(world, "square_log").z(), 0.0, 0.01);
  EXPECT_NEAR(centre(world, "round_log").z(), 0.0, 0.01);
  const engine::ParticleStore& particles = world.particles();
  const Vec3 bead = particles.positions().col(*particles.find(*particles.findByName("bead")));
  EXPECT_LT(bead.z(), centre(world, "crate").z() - 0.25 - 0.3);  // below it, the bungee taut
}

}  // namespace
}  // namespace node
}  // namespace mass_aggregate_sim
