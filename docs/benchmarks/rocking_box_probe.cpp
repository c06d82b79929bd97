// A lone box on the ground, released tilted about y onto one edge (docs/BENCHMARKS.md,
// 2026-11-28 session 20): with restitution 0 it should rock back and settle on its base. Prints,
// every EVERY frames (60 unless set), the kinetic energy, |w| and the centre's height. Build from
// the repository root after scripts/bench.sh has built the engine:
//   g++ -std=c++17 -O2 -I include -I test/engine/bodies -I /usr/include/eigen3 \
//     docs/benchmarks/rocking_box_probe.cpp -o /tmp/rocking_box_probe \
//     -L ~/mass_aggregate_sim_ws/devel/lib -lmass_aggregate_sim_engine \
//     -Wl,-rpath,$HOME/mass_aggregate_sim_ws/devel/lib
//   /tmp/rocking_box_probe 2 0.1225 0.105 0.276 0.027  # tilt (degrees), half extents, mass
// Switches (sleeping is off): NOGUESS, NOSHOCK, NOCCD, SUB=n, ITER=n, RELAX=n, HZ=x (contact
// hertz), SPEC=x (speculative distance), PUSH=x (max push speed), MU=x (friction, 0.5).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "body_scenes.h"
using namespace mass_aggregate_sim::engine;
using namespace mass_aggregate_sim::engine::test_bodies;

int main(int argc, char** argv) {
  if (argc < 6) {
    std::fprintf(stderr, "usage: %s tilt_degrees hx hy hz mass\n", argv[0]);
    return 2;
  }
  const double degrees = atof(argv[1]);
  const Vec3 half(atof(argv[2]), atof(argv[3]), atof(argv[4]));
  const double mass = atof(argv[5]);
  const int every = getenv("EVERY") ? atoi(getenv("EVERY")) : 60;
  World world(config());
  BodySettings s = world.bodySettings();
  s.sleep = false;
  if (getenv("NOGUESS")) s.guess_loads = false;
  if (getenv("NOSHOCK")) s.shock_propagation = false;
  if (getenv("NOCCD")) s.continuous = false;
  if (getenv("SUB")) s.substeps = atoi(getenv("SUB"));
  if (getenv("ITER")) s.iterations = atoi(getenv("ITER"));
  if (getenv("RELAX")) s.relax_iterations = atoi(getenv("RELAX"));
  if (getenv("HZ")) s.contact_hertz = atof(getenv("HZ"));
  if (getenv("SPEC")) s.speculative_distance = atof(getenv("SPEC"));
  if (getenv("PUSH")) s.max_push_speed = atof(getenv("PUSH"));
  if (!world.setBodySettings(s)) return 1;
  const double mu = getenv("MU") ? atof(getenv("MU")) : 0.5;
  addGround(world, Material{0.0, mu});
  const Quat q(Eigen::AngleAxisd(degrees * M_PI / 180.0, Vec3::UnitY()));
  // Placed with its lowest corner on the ground.
  double lowest = 0.0;
  for (int c = 0; c < 8; ++c) {
    const Vec3 corner((c & 1 ? 1 : -1) * half.x(), (c & 2 ? 1 : -1) * half.y(),
                      (c & 4 ? 1 : -1) * half.z());
    lowest = std::min(lowest, (q * corner).z());
  }
  const BodyId id =
      *world.addBody(body(box(half, Material{0.0, mu}), mass, Vec3(0.0, 0.0, -lowest), q));
  const std::size_t i = *world.bodies().find(id);
  for (int f = 1; f <= 600; ++f) {
    world.step();
    if (f % every == 0) {
      std::printf("t %.2f KE %.3g J |w| %.3f rad/s z %.5f m\n", f / 60.0, world.kineticEnergy(),
                  world.bodies().angularVelocity(i).norm(), world.bodies().position(i).z());
    }
  }
}
