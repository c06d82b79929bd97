// Grains on an awake box (docs/BENCHMARKS.md, 2026-11-29 session 29): how far the lowest grain of
// a column goes into the box's top face, from the test scenes (test/engine/bodies/body_scenes.h:
// a 0.5 m box of 20 kg, grains of 5 cm and 50 g, restitution 0.1 and friction 0.3, 60 Hz).
// Scenes (first argument):
//   column SPEED   eight grains land on the box resting on the ground at SPEED m/s; MODE=1 makes
//                  the box fixed, MODE=2 a BoxCollider
//   fall           the box carries four grains and falls 2 m onto the ground
//   lift           a kinematic box lifts four grains at 1 m/s for 1 s, then stops
// Prints the deepest the lowest grain went into the box (gap < 0), the widest gap while the box
// flew (fall), and the gap at the end (4 s). Build and run from the repository root after
// scripts/bench.sh has built the engine:
//   g++ -std=c++17 -O2 -I include -I /usr/include/eigen3 \
//     docs/benchmarks/grains_on_moving_box_probe.cpp -o /tmp/grains_on_moving_box_probe \
//     -L ~/mass_aggregate_sim_ws/devel/lib -lmass_aggregate_sim_engine \
//     -Wl,-rpath,$HOME/mass_aggregate_sim_ws/devel/lib
//   /tmp/grains_on_moving_box_probe column 3
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "../../test/engine/bodies/body_scenes.h"
using namespace mass_aggregate_sim::engine;
using namespace mass_aggregate_sim::engine::test_bodies;
int main(int argc, char** argv) {
  const std::string scene = argc > 1 ? argv[1] : "column";
  const Real speed = argc > 2 ? std::atof(argv[2]) : 3.0;
  const int mode = std::getenv("MODE") ? std::atoi(std::getenv("MODE")) : 0;
  World world(config());
  addGround(world);
  CollisionSettings collisions;
  collisions.particle_collisions = true;
  collisions.particle_restitution = 0.1;
  collisions.particle_friction = 0.3;
  world.setCollisionSettings(collisions);
  const Real z0 = scene == "fall" ? 2.25 : 0.25;
  BodySpec spec = body(box(Vec3::Constant(0.25)), 20.0, Vec3(0.0, 0.0, z0));
  if (scene == "lift") {
    spec.type = BodyType::kKinematic;
    spec.linear_velocity = Vec3(0.0, 0.0, 1.0);
  }
  if (mode == 1) spec.type = BodyType::kFixed;
  std::optional<BodyId> id;
  if (mode == 2) {
    BoxCollider collider;
    collider.center = Vec3(0.0, 0.0, 0.25);
    collider.half_extents = Vec3::Constant(0.25);
    collider.material = {0.0, 0.5};
    world.addCollider(collider);
  } else {
    id = *world.addBody(spec);
  }
  const int count = scene == "column" ? 8 : 4;
  for (int k = 0; k < count; ++k) {
    ParticleSpec grain;
    grain.position = scene == "column" ? Vec3(0.0, 0.0, 0.56 + 2.0 * kGrainRadius * k)
                                       : Vec3(0.0, 0.0, z0 + 0.25 + kGrainRadius * (1 + 2 * k));
    grain.velocity = scene == "column" ? Vec3(0.0, 0.0, -speed) : Vec3::Zero();
    grain.radius = kGrainRadius;
    grain.inverse_mass = 20.0;
    world.addParticle(grain);
  }
  Real deepest = 0.0, widest_in_flight = 0.0, gap = 0.0;
  for (int step = 0; step < 240; ++step) {
    if (scene == "lift" && step == 60) world.setBodyVelocity(*id, Vec3::Zero(), Vec3::Zero());
    world.step();
    const Real box_z = id ? world.bodies().position(*world.bodies().find(*id)).z() : 0.25;
    gap = world.particles().positions()(2, 0) - kGrainRadius - (box_z + 0.25);
    deepest = std::min(deepest, gap);
    if (scene == "fall" && box_z > 0.3) widest_in_flight = std::max(widest_in_flight, gap);
  }
  std::printf("%s %.1f mode %d: deepest %.5f m, widest gap in flight %.5f m, at the end %.6f m\n",
              scene.c_str(), speed, mode, deepest, widest_in_flight, gap);
}
