// Where the particle rain's spheres leave the walls (docs/BENCHMARKS.md, 2026-11-28 session 22):
// over the walls' top (thrown, physics) or below it (through a wall). 4 x 2, sleeping off, 10 s.
// Build and run from the repository root:
//   g++ -std=c++17 -O2 -I include -I bench/rigid -I /usr/include/eigen3 \
//     docs/benchmarks/rain_escape_probe.cpp bench/rigid/rigid_scenes.cpp -o DIR/rain_escape_probe \
//     -L DIR -lmass_aggregate_sim_engine
//   LD_LIBRARY_PATH=DIR DIR/rain_escape_probe SEED
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "engine_scene.h"
#include "mass_aggregate_sim/engine/world/world.h"
using namespace mass_aggregate_sim;
using engine::Vec3;
int main(int argc, char** argv) {
  const std::uint64_t seed = std::strtoull(argv[1], nullptr, 10);
  const auto scene = bench::rigid::particleRain(2000, seed);
  engine::BodySettings settings;
  settings.sleep = false;
  std::vector<engine::BodyId> ids;
  engine::World world = bench::rigid::engineWorld(scene, settings, &ids);
  std::vector<char> out(ids.size(), 0);
  std::vector<Vec3> prev(ids.size());
  int above = 0, below = 0, from_top = 0;
  double min_z = 1e9;
  for (std::size_t k = 0; k < ids.size(); ++k) prev[k] = scene.bodies[k].position;
  for (int f = 0; f < 600; ++f) {
    world.step();
    const auto& b = world.bodies();
    for (std::size_t k = 0; k < ids.size(); ++k) {
      if (scene.bodies[k].isFixed()) continue;
      const Vec3 p = b.position(*b.find(ids[k]));
      if (!out[k] && bench::rigid::hasEscaped(scene, p)) {
        out[k] = 1;
        const double z = 0.5 * (p.z() + prev[k].z());
        min_z = std::min(min_z, z);
        if (z > scene.wall_height)
          ++above;
        else
          ++below;
      }
      prev[k] = p;
    }
  }
  std::printf("seed %llu: %d escaped above the walls' top, %d below (lowest crossing %.3f m)\n",
              (unsigned long long)seed, above, below, min_z);
}
