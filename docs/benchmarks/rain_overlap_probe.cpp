// The particle rain's deepest overlaps over its last 3 s, by the kinds of contact that make them
// (docs/BENCHMARKS.md, 2026-11-28 session 22): s a sphere, B a box, W a wall, G the ground;
// "after fall" when a body of the contact was in free fall within the 10 frames before. Also how
// far the top cube moved and how many spheres are outside the walls at 10 s. Build and run from
// the repository root (4 x 2, sleeping off; SUBSTEPS=n, ITER=n otherwise; VERBOSE=1 prints every
// frame's deepest contact):
//   g++ -std=c++17 -O2 -I include -I bench/rigid -I /usr/include/eigen3 \
//     docs/benchmarks/rain_overlap_probe.cpp bench/rigid/rigid_scenes.cpp -o DIR/rain_overlap_probe
//     \ -L DIR -lmass_aggregate_sim_engine
//   LD_LIBRARY_PATH=DIR DIR/rain_overlap_probe SEED
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <vector>

#include "engine_scene.h"
#include "mass_aggregate_sim/engine/world/world.h"
using namespace mass_aggregate_sim;
using engine::Vec3;
int main(int argc, char** argv) {
  const std::uint64_t seed = argc > 1 ? std::strtoull(argv[1], nullptr, 10) : 2;
  const auto scene = bench::rigid::particleRain(2000, seed);
  engine::BodySettings settings;
  settings.sleep = false;
  if (std::getenv("SUBSTEPS")) settings.substeps = std::atoi(std::getenv("SUBSTEPS"));
  if (std::getenv("ITER")) settings.iterations = std::atoi(std::getenv("ITER"));
  std::vector<engine::BodyId> ids;
  engine::World world = bench::rigid::engineWorld(scene, settings, &ids);
  std::map<std::uint64_t, std::size_t> index_of;
  const auto key = [](engine::BodyId id) {
    return (std::uint64_t(id.index) << 32) | id.generation;
  };
  for (std::size_t k = 0; k < ids.size(); ++k) index_of[key(ids[k])] = k;
  const auto kind = [&](std::size_t k) {
    if (scene.bodies[k].isFixed()) return 'W';
    return scene.bodies[k].shape == bench::rigid::ShapeType::kSphere ? 's' : 'B';
  };
  std::vector<int> last_free(ids.size(), -1000);
  std::vector<Vec3> prev_v(ids.size(), Vec3::Zero());
  double mean = 0;
  std::map<std::string, double> by_pair;
  std::map<std::string, int> n_by_pair;
  int recent_fall = 0;
  const bool verbose = std::getenv("VERBOSE") != nullptr;
  for (int f = 0; f < 600; ++f) {
    world.step();
    const auto& b = world.bodies();
    for (std::size_t k = 0; k < ids.size(); ++k) {
      if (scene.bodies[k].isFixed()) continue;
      const Vec3 v = b.linearVelocity(*b.find(ids[k]));
      if ((v - prev_v[k] - scene.gravity * (1.0 / 60)).norm() < 1e-6) last_free[k] = f;
      prev_v[k] = v;
    }
    if (f < 420) continue;
    double deepest = 0;
    const engine::BodyContactReport* worst = nullptr;
    for (const auto& c : world.bodyContacts())
      for (const auto& p : c.points)
        if (-p.separation > deepest) {
          deepest = -p.separation;
          worst = &c;
        }
    mean += deepest / 180;
    if (!worst) continue;
    const std::size_t a = index_of[key(worst->body)];
    std::string pair(1, kind(a));
    int fell = f - last_free[a];
    if (worst->other == engine::BodyContactReport::Other::kBody) {
      const std::size_t o = index_of[key(worst->other_body)];
      pair += kind(o);
      if (!scene.bodies[o].isFixed()) fell = std::min(fell, f - last_free[o]);
    } else {
      pair += 'G';
    }
    const bool recent = fell <= 10;
    recent_fall += recent;
    by_pair[pair + (recent ? " after fall" : "")] += deepest / 180;
    n_by_pair[pair + (recent ? " after fall" : "")] += 1;
    if (verbose)
      std::printf("f %d deepest %.2f mm %s body %zu fell %d frames ago z %.3f\n", f, 1e3 * deepest,
                  pair.c_str(), a, fell, b.position(*b.find(worst->body)).z());
  }
  {
    const auto& b = world.bodies();
    const auto top = static_cast<std::size_t>(scene.top_body);
    const double moved = (b.position(*b.find(ids[top])) - scene.bodies[top].position).norm();
    int escaped = 0;
    for (std::size_t k = 0; k < ids.size(); ++k)
      if (!scene.bodies[k].isFixed() &&
          bench::rigid::hasEscaped(scene, b.position(*b.find(ids[k]))))
        ++escaped;
    std::printf("seed %llu top moved %.2f mm escaped %d ", (unsigned long long)seed, 1e3 * moved,
                escaped);
  }
  std::printf(
      "late mean %.3f mm; frames whose deepest involves a body in free fall within 10 frames: %d "
      "of 180\n",
      1e3 * mean, recent_fall);
  for (auto& [p, m] : by_pair)
    std::printf("  %-14s frames %3d, share of the late mean %.3f mm\n", p.c_str(), n_by_pair[p],
                1e3 * m);
}
