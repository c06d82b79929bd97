// The accuracy study's dropped column (bench/study/stack_problems.cpp: ten unit cubes 1 cm apart,
// alternately 5 cm off-centre and turned 5 degrees, friction 0.5, sleeping off) after 10 s at the
// body solver's substeps and iterations given on the command line: prints how far the farthest
// cube is, horizontally, from where it was placed, and the kinetic energy (docs/ACCURACY.md,
// session 35). Build and run from the repository root after scripts/accuracy_study.sh has built
// the engine:
//   g++ -std=c++17 -O2 -I include -I bench/study -I /usr/include/eigen3 \
//     docs/benchmarks/dropped_column_walk_probe.cpp bench/study/body_scene.cpp \
//     -o /tmp/dropped_column_walk_probe -L ~/mass_aggregate_sim_ws/devel/lib \
//     -lmass_aggregate_sim_engine -Wl,-rpath,$HOME/mass_aggregate_sim_ws/devel/lib
//   /tmp/dropped_column_walk_probe 1 1
// Output on 2026-11-30 (farthest cube in m, kinetic energy in J), 2c6dfa8's engine:
//   1 1: 5.0322e-01 2.789e-03
//   2 1: 1.0446e-02 6.421e-05
//   4 2: 7.6723e-03 3.069e-07
// and with the engine of 8bd1c19 (session 12), its sources compiled with the Release flags:
//   1 1: 9.9086e-02 6.946e-03
//   2 1: 1.3428e-02 4.889e-05
//   4 2: 8.1895e-03 2.260e-06
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "body_scene.h"

using namespace mass_aggregate_sim::study;

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: %s SUBSTEPS ITERATIONS\n", argv[0]);
    return 2;
  }
  BodyKnobs knobs;
  knobs.substeps = std::atoi(argv[1]);
  knobs.iterations = std::atoi(argv[2]);
  World world = bodyWorld(knobs, kG);
  const Material material{0.0, 0.5};
  addGround(world, material);
  std::vector<BodyId> ids;
  for (int k = 0; k < 10; ++k) {
    const Real sign = k % 2 == 0 ? -1.0 : 1.0;
    const Quat turn(Eigen::AngleAxisd(sign * 5.0 * M_PI / 180.0, Vec3::UnitZ()));
    ids.push_back(addBox(world, Vec3::Constant(0.5), 1.0, Vec3(sign * 0.05, 0.0, 0.5 + k * 1.01),
                         material, turn));
  }
  for (int step = 1; step <= 600; ++step) world.step();
  Real farthest = 0.0;
  for (int k = 0; k < 10; ++k) {
    const Real sign = k % 2 == 0 ? -1.0 : 1.0;
    const Vec3 p = world.bodies().position(*world.bodies().find(ids[k]));
    farthest = std::max(farthest, std::hypot(p.x() - sign * 0.05, p.y()));
  }
  std::printf("%s %s: %.4e %.3e\n", argv[1], argv[2], farthest, world.kineticEnergy());
  return 0;
}
