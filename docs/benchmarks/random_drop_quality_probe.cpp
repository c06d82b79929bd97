// The random drop's quality at 10 s, one line per seed (docs/BENCHMARKS.md, 2026-11-28 session
// 24): the mean and worst of the frames' deepest overlaps over the last 3 s, the kinetic energy
// (linear and angular) at 10 s, and how many boxes moved more than 1 cm in the last 3 s. 4 x 2,
// sleeping off; SUB=n substeps, ITERS=n iterations otherwise. Build and run from the repository
// root:
//   g++ -std=c++17 -O2 -I include -I bench/rigid -I /usr/include/eigen3 \
//     docs/benchmarks/random_drop_quality_probe.cpp bench/rigid/rigid_scenes.cpp \
//     -o DIR/random_drop_quality_probe -L DIR -lmass_aggregate_sim_engine
//   for s in $(seq 1 24); do LD_LIBRARY_PATH=DIR DIR/random_drop_quality_probe $s; done
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "engine_scene.h"
#include "mass_aggregate_sim/engine/world/world.h"

using namespace mass_aggregate_sim;
using engine::Vec3;

int main(int argc, char** argv) {
  const int seed = argc > 1 ? std::atoi(argv[1]) : 1;
  const auto scene = bench::rigid::randomDrop(1000, seed);
  engine::BodySettings settings;
  settings.sleep = false;
  if (std::getenv("SUB")) settings.substeps = std::atoi(std::getenv("SUB"));
  if (std::getenv("ITERS")) settings.iterations = std::atoi(std::getenv("ITERS"));
  std::vector<engine::BodyId> ids;
  engine::World world = bench::rigid::engineWorld(scene, settings, &ids);
  const auto& bodies = world.bodies();
  double late_mean = 0.0;
  double late_worst = 0.0;
  std::vector<Vec3> at_7s;
  for (int frame = 0; frame < 600; ++frame) {
    world.step();
    if (frame == 419) {
      for (const auto id : ids) at_7s.push_back(bodies.position(*bodies.find(id)));
    }
    if (frame < 420) continue;
    double deepest = 0.0;
    for (const auto& c : world.bodyContacts()) {
      for (const auto& p : c.points) deepest = std::max(deepest, -p.separation);
    }
    late_mean += deepest / 180.0;
    late_worst = std::max(late_worst, deepest);
  }
  double kinetic = 0.0;
  int moved = 0;
  for (std::size_t k = 0; k < ids.size(); ++k) {
    if (scene.bodies[k].isFixed()) continue;
    const std::size_t i = *bodies.find(ids[k]);
    const Vec3 w = bodies.orientation(i).conjugate() * bodies.angularVelocity(i);
    kinetic += 0.5 * (bodies.mass(i) * bodies.linearVelocity(i).squaredNorm() +
                      w.dot(bodies.principalInertia(i).cwiseProduct(w)));
    if ((bodies.position(i) - at_7s[k]).norm() > 0.01) ++moved;
  }
  std::printf("seed %d late mean %.3f mm worst %.2f mm KE %.2e J moved>1cm %d\n", seed,
              late_mean * 1e3, late_worst * 1e3, kinetic, moved);
}
