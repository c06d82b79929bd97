// Spheres falling onto a resting bed of spheres (docs/BENCHMARKS.md, 2026-11-28 session 24): the
// rain's 3 cm, 100 g spheres, a two-layer bed of 481 on the ground and 20 more dropped one after
// another from H metres (5 by default) at random spots over it. Prints the mean and the worst of
// the frames' deepest overlaps from 0.5 s to 5 s and the kinetic energy at 5 s. 4 x 2, sleeping
// off; SUB=n substeps. Build and run from the repository root:
//   g++ -std=c++17 -O2 -I include -I bench/rigid -I /usr/include/eigen3 \
//     docs/benchmarks/sphere_bed_impact_probe.cpp bench/rigid/rigid_scenes.cpp \
//     -o DIR/sphere_bed_impact_probe -L DIR -lmass_aggregate_sim_engine
//   LD_LIBRARY_PATH=DIR DIR/sphere_bed_impact_probe SEED
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "engine_scene.h"
#include "mass_aggregate_sim/engine/world/world.h"

using namespace mass_aggregate_sim;
using namespace mass_aggregate_sim::bench::rigid;

BodySpec rainSphere(const Eigen::Vector3d& position) {
  BodySpec sphere;
  sphere.shape = ShapeType::kSphere;
  sphere.radius = kRainSphereRadius;
  sphere.mass = kRainSphereMass;
  sphere.position = position;
  return sphere;
}

int main(int argc, char** argv) {
  const int seed = argc > 1 ? std::atoi(argv[1]) : 1;
  const double height = std::getenv("H") ? std::atof(std::getenv("H")) : 5.0;
  const double r = kRainSphereRadius;
  const int per_side = 16;
  const double spacing = 2.0 * r + 1e-4;
  RigidScene scene;
  scene.name = "sphere_bed";
  // A square layer on the ground, the second in its hollows.
  for (int layer = 0; layer < 2; ++layer) {
    for (int i = 0; i < per_side - layer; ++i) {
      for (int j = 0; j < per_side - layer; ++j) {
        scene.bodies.push_back(
            rainSphere(Eigen::Vector3d((i + 0.5 * layer) * spacing, (j + 0.5 * layer) * spacing,
                                       r + 1e-5 + layer * std::sqrt(2.0) * r * 1.001)));
      }
    }
  }
  SplitMix64 rng(seed);
  for (int k = 0; k < 20; ++k) {
    const double x = rng.uniform(0.2, 0.7);
    const double y = rng.uniform(0.2, 0.7);
    scene.bodies.push_back(rainSphere(Eigen::Vector3d(x, y, height + 0.4 * k)));
  }
  engine::BodySettings settings;
  settings.sleep = false;
  if (std::getenv("SUB")) settings.substeps = std::atoi(std::getenv("SUB"));
  std::vector<engine::BodyId> ids;
  engine::World world = engineWorld(scene, settings, &ids);
  double sum_deepest = 0.0;
  double worst = 0.0;
  int frames = 0;
  for (int frame = 0; frame < 300; ++frame) {
    world.step();
    double deepest = 0.0;
    for (const auto& c : world.bodyContacts()) {
      for (const auto& p : c.points) deepest = std::max(deepest, -p.separation);
    }
    if (frame < 30) continue;
    sum_deepest += deepest;
    worst = std::max(worst, deepest);
    ++frames;
  }
  const auto& bodies = world.bodies();
  double kinetic = 0.0;
  for (const auto id : ids) {
    kinetic += 0.5 * kRainSphereMass * bodies.linearVelocity(*bodies.find(id)).squaredNorm();
  }
  std::printf("seed %d H %.1f: mean deepest %.3f mm, worst %.3f mm, KE at 5 s %.4f J\n", seed,
              height, sum_deepest / frames * 1e3, worst * 1e3, kinetic);
}
