// The particle rain with its walls raised to WALL metres (9 keeps every sphere in), so that runs
// compare their late overlap over the same number of spheres (docs/BENCHMARKS.md, 2026-11-28
// session 24). Prints the mean and the median of the frames' deepest overlaps over the last 3 s,
// the spheres' kinetic energy (linear and angular) averaged over those frames, and how many bodies
// are inside the walls at 10 s. 4 x 2, sleeping off; SUB=n substeps. Build and run from the
// repository root:
//   g++ -std=c++17 -O2 -I include -I bench/rigid -I /usr/include/eigen3 \
//     docs/benchmarks/rain_tall_walls_probe.cpp bench/rigid/rigid_scenes.cpp \
//     -o DIR/rain_tall_walls_probe -L DIR -lmass_aggregate_sim_engine
//   WALL=9 LD_LIBRARY_PATH=DIR DIR/rain_tall_walls_probe SEED
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "engine_scene.h"
#include "mass_aggregate_sim/engine/world/world.h"

using namespace mass_aggregate_sim;
using bench::rigid::ShapeType;

int main(int argc, char** argv) {
  const int seed = argc > 1 ? std::atoi(argv[1]) : 2;
  auto scene = bench::rigid::particleRain(2000, seed);
  if (std::getenv("WALL")) {
    const double height = std::atof(std::getenv("WALL"));
    for (auto& body : scene.bodies) {
      // The four walls are the fixed boxes; the stack's cubes are dynamic.
      if (!body.isFixed() || body.shape != ShapeType::kBox) continue;
      body.half_extents.z() = 0.5 * height;
      body.position.z() = 0.5 * height;
    }
    scene.wall_height = height;
  }
  engine::BodySettings settings;
  settings.sleep = false;
  if (std::getenv("SUB")) settings.substeps = std::atoi(std::getenv("SUB"));
  std::vector<engine::BodyId> ids;
  engine::World world = bench::rigid::engineWorld(scene, settings, &ids);
  const auto& bodies = world.bodies();
  std::vector<double> deepest_per_frame;
  double late_mean = 0.0;
  double sphere_kinetic = 0.0;
  for (int frame = 0; frame < 600; ++frame) {
    world.step();
    if (frame < 420) continue;
    double deepest = 0.0;
    for (const auto& c : world.bodyContacts()) {
      for (const auto& p : c.points) deepest = std::max(deepest, -p.separation);
    }
    deepest_per_frame.push_back(deepest);
    late_mean += deepest / 180.0;
    for (std::size_t k = 0; k < ids.size(); ++k) {
      const auto& spec = scene.bodies[k];
      if (spec.shape != ShapeType::kSphere) continue;
      const std::size_t i = *bodies.find(ids[k]);
      const double r = spec.radius;
      sphere_kinetic += (0.5 * spec.mass * bodies.linearVelocity(i).squaredNorm() +
                         0.2 * spec.mass * r * r * bodies.angularVelocity(i).squaredNorm()) /
                        180.0;
    }
  }
  int inside = 0;
  for (std::size_t k = 0; k < ids.size(); ++k) {
    if (scene.bodies[k].isFixed()) continue;
    if (!bench::rigid::hasEscaped(scene, bodies.position(*bodies.find(ids[k])))) ++inside;
  }
  std::sort(deepest_per_frame.begin(), deepest_per_frame.end());
  std::printf("seed %d late mean %.3f mm, median frame %.3f mm, spheres' KE %.2f J, inside %d\n",
              seed, late_mean * 1e3, deepest_per_frame[90] * 1e3, sphere_kinetic, inside);
}
