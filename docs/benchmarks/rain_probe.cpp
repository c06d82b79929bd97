// The particle rain's stack, over seeds (docs/BENCHMARKS.md, 2026-11-27 session 11): 2,000 spheres
// of the rain scene fall on the stack of five unit cubes between walls; after 10 s, how far the
// top cube moved and how many spheres left the walls. Build and run from the repository root:
//   g++ -std=c++17 -O2 -I include -I bench/rigid -I /usr/include/eigen3 \
//     docs/benchmarks/rain_probe.cpp bench/rigid/rigid_scenes.cpp -o DIR/rain_probe \
//     -L DIR -lmass_aggregate_sim_engine
//   LD_LIBRARY_PATH=DIR DIR/rain_probe 1 2 3   # seeds; SUBSTEPS=n, ITER=n: other than 4 x 2;
//   NOSHOCK=1: shock propagation off
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "engine_scene.h"
#include "mass_aggregate_sim/engine/world/world.h"
using namespace mass_aggregate_sim;
using engine::Vec3;
int main(int argc, char** argv) {
  for (int arg = 1; arg < argc; ++arg) {
    const std::uint64_t seed = std::strtoull(argv[arg], nullptr, 10);
    const auto scene = bench::rigid::particleRain(2000, seed);
    engine::BodySettings settings;
    settings.sleep = false;
    if (std::getenv("SUBSTEPS")) settings.substeps = std::atoi(std::getenv("SUBSTEPS"));
    if (std::getenv("ITER")) settings.iterations = std::atoi(std::getenv("ITER"));
    if (std::getenv("NOSHOCK")) settings.shock_propagation = false;
    std::vector<engine::BodyId> ids;
    engine::World world = bench::rigid::engineWorld(scene, settings, &ids);
    for (int f = 0; f < 600; ++f) world.step();
    const auto& bodies = world.bodies();
    const auto top = static_cast<std::size_t>(scene.top_body);
    const Vec3 moved = bodies.position(*bodies.find(ids[top])) - scene.bodies[top].position;
    int escaped = 0;
    for (std::size_t k = 0; k < ids.size(); ++k) {
      const Vec3& p = bodies.position(*bodies.find(ids[k]));
      if (std::abs(p.x()) > scene.inner_half_width || std::abs(p.y()) > scene.inner_half_width) {
        ++escaped;
      }
    }
    std::printf("seed %llu: top moved %.4f m (%.4f %.4f %.4f), %d outside the walls, KE %.3g J\n",
                static_cast<unsigned long long>(seed), moved.norm(), moved.x(), moved.y(),
                moved.z(), escaped, world.kineticEnergy());
  }
}
