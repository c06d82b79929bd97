// The heavy-on-light column at 1 substep and 1 iteration (docs/ACCURACY.md, rigid bodies): ten
// unit cubes, alternately 1 kg and 100 kg (1 kg at the bottom), friction 0.5, sleeping off; the
// top's position and velocity at the first steps and every half second. Build and run from the
// repository root after scripts/bench.sh has built the engine:
//   g++ -std=c++17 -O2 -I include -I /usr/include/eigen3 docs/benchmarks/heavy_light_probe.cpp \
//     -o /tmp/heavy_light_probe -L ~/mass_aggregate_sim_ws/devel/lib -lmass_aggregate_sim_engine \
//     -Wl,-rpath,$HOME/mass_aggregate_sim_ws/devel/lib
//   /tmp/heavy_light_probe 1 1 600   # substeps, iterations, frames
#include <cstdio>
#include <cstdlib>

#include "mass_aggregate_sim/engine/world/world.h"
using namespace mass_aggregate_sim;
using engine::Vec3;
int main(int argc, char** argv) {
  engine::WorldConfig config;
  config.dt = 1.0 / 60.0;
  config.gravity = Vec3(0, 0, -9.81);
  engine::World world = *engine::World::create(config);
  engine::BodySettings settings;
  settings.substeps = argc > 1 ? atoi(argv[1]) : 1;
  settings.iterations = argc > 2 ? atoi(argv[2]) : 1;
  settings.sleep = false;
  if (getenv("NOSHOCK")) settings.shock_propagation = false;
  if (getenv("NOGUESS")) settings.guess_loads = false;
  if (getenv("RELAX")) settings.relax_iterations = atoi(getenv("RELAX"));
  world.setBodySettings(settings);
  engine::PlaneCollider ground;
  ground.normal = Vec3::UnitZ();
  ground.offset = 0;
  const double mu = getenv("MU") ? atof(getenv("MU")) : 0.5;
  ground.material = {0, mu};
  world.addCollider(ground);
  engine::BodyId top;
  for (int k = 0; k < 10; ++k) {
    engine::BodySpec body;
    body.type = engine::BodyType::kDynamic;
    body.pose.position = Vec3(0, 0, 0.5 + k);
    engine::BodyShapeSpec shape;
    shape.geometry = engine::BoxShape{Vec3::Constant(0.5)};
    shape.material = {0, mu};
    body.shapes = {shape};
    body.mass = k % 2 == 0 ? 1.0 : 100.0;
    top = *world.addBody(body);
  }
  const std::size_t i = *world.bodies().find(top);
  const int frames = argc > 3 ? atoi(argv[3]) : 600;
  for (int f = 1; f <= frames; ++f) {
    world.step();
    if (f % 30 == 0 || f < 6) {
      const auto& b = world.bodies();
      std::printf("f %d top (%.4f %.4f %.4f) v (%.3g %.3g %.3g) w %.3g\n", f, b.position(i).x(),
                  b.position(i).y(), b.position(i).z(), b.linearVelocity(i).x(),
                  b.linearVelocity(i).y(), b.linearVelocity(i).z(), b.angularVelocity(i).norm());
    }
  }
}
