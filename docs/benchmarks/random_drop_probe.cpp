// The random drop's deepest overlaps, looked at one by one (docs/BENCHMARKS.md, 2026-11-26).
// Build and run from the repository root after scripts/bench.sh has built the engine:
//   g++ -std=c++17 -O2 -I include -I bench/rigid -I /usr/include/eigen3 \
//     docs/benchmarks/random_drop_probe.cpp bench/rigid/rigid_scenes.cpp \
//     -o /tmp/random_drop_probe -L ~/mass_aggregate_sim_ws/devel/lib -lmass_aggregate_sim_engine \
//     -Wl,-rpath,$HOME/mass_aggregate_sim_ws/devel/lib
//   /tmp/random_drop_probe 4 600              # substeps, frames
//   NOGRAVITY=1 /tmp/random_drop_probe 4 600  # then the deepest pair with gravity off, at rest
// Environment: SEED=n the scene's seed (1, the benchmark's, by default), ITER=n iterations,
// RELAX=n relaxing passes, PUSH=x max_push_speed, NOGUESS=1 no load guesses, NOSHOCK=1 no shock
// pass, SLEEP=1 sleeping on (each second then also counts the dynamic boxes asleep). Besides the
// kinetic energy and the deepest overlap each second it prints
// (docs/benchmarks/rigid_2026-11-27_session10_random_drop_ke.sh sums those up), for the last 3 s
// (180 frames), the worst and the mean of the frames' deepest overlaps and the linear kinetic
// energy at the end ("late"), and for the deepest pair at the end the least overlap over the 15
// axes of the separating axis test, computed here from the two boxes alone.
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "engine_scene.h"
#include "mass_aggregate_sim/engine/world/world.h"
using namespace mass_aggregate_sim;
using engine::Vec3;
int main(int argc, char** argv) {
  const int substeps = argc > 1 ? atoi(argv[1]) : 4;
  const int frames = argc > 2 ? atoi(argv[2]) : 600;
  const std::uint64_t seed = getenv("SEED") ? std::strtoull(getenv("SEED"), nullptr, 10) : 1;
  const auto scene = bench::rigid::randomDrop(1000, seed);
  engine::BodySettings settings;
  settings.substeps = substeps;
  settings.sleep = getenv("SLEEP") != nullptr;
  if (getenv("ITER")) settings.iterations = atoi(getenv("ITER"));
  if (getenv("RELAX")) settings.relax_iterations = atoi(getenv("RELAX"));
  if (getenv("NOGUESS")) settings.guess_loads = false;
  if (getenv("PUSH")) settings.max_push_speed = atof(getenv("PUSH"));
  if (getenv("NOSHOCK")) settings.shock_propagation = false;
  engine::World world = bench::rigid::engineWorld(scene, settings);
  constexpr int kLate = 180;
  double late_worst = 0, late_sum = 0;
  for (int f = 0; f < frames; ++f) {
    world.step();
    {
      double deepest = 0;
      for (const auto& c : world.bodyContacts())
        for (const auto& p : c.points) deepest = std::max(deepest, -p.separation);
      if (f >= frames - kLate) {
        late_worst = std::max(late_worst, deepest);
        late_sum += deepest;
      }
    }
    if (f % 60 == 59) {
      double worst = 0;
      int n = 0;
      for (const auto& c : world.bodyContacts())
        for (const auto& p : c.points) {
          worst = std::max(worst, -p.separation);
          if (-p.separation > 0.01) ++n;
        }
      int asleep = 0;
      const auto& bodies = world.bodies();
      for (std::size_t i = 0; i < bodies.size(); ++i) {
        asleep += bodies.dynamic(i) && !bodies.awake(i) ? 1 : 0;
      }
      std::printf("t %.0f s: KE %.3g J deepest %.4f m, points deeper than 1 cm: %d, asleep %d\n",
                  (f + 1) / 60.0, world.kineticEnergy(), worst, n, asleep);
    }
  }
  {
    double linear = 0;
    const auto& bs = world.bodies();
    for (std::size_t i = 0; i < bs.size(); ++i)
      if (bs.dynamic(i)) linear += 0.5 * bs.mass(i) * bs.linearVelocity(i).squaredNorm();
    std::printf(
        "late: worst %.4f m, mean of the frames' deepest %.4f m; linear KE at the end %.3g J\n",
        late_worst, late_sum / std::min(kLate, frames), linear);
  }
  struct Deep {
    double depth;
    engine::BodyContactReport c;
    Vec3 p;
  };
  std::vector<Deep> deep;
  for (const auto& c : world.bodyContacts())
    for (const auto& p : c.points)
      if (-p.separation > 0.01) deep.push_back({-p.separation, c, p.position});
  std::sort(deep.begin(), deep.end(),
            [](const Deep& a, const Deep& b) { return a.depth > b.depth; });
  const auto& bodies = world.bodies();
  for (std::size_t k = 0; k < std::min<std::size_t>(8, deep.size()); ++k) {
    const auto& d = deep[k];
    const std::size_t a = *bodies.find(d.c.body);
    const auto* shape =
        std::get_if<engine::BoxShape>(&bodies.shapes()[bodies.shapesOf(a)[0]].geometry);
    std::printf(
        "depth %.4f other %d normal (%.2f %.2f %.2f) at (%.2f %.2f %.2f); a half (%.3f %.3f %.3f) "
        "v %.3f w %.3f mass %.3f",
        d.depth, (int)d.c.other, d.c.normal.x(), d.c.normal.y(), d.c.normal.z(), d.p.x(), d.p.y(),
        d.p.z(), shape->half_extents.x(), shape->half_extents.y(), shape->half_extents.z(),
        bodies.linearVelocity(a).norm(), bodies.angularVelocity(a).norm(), bodies.mass(a));
    if (d.c.other == engine::BodyContactReport::Other::kBody) {
      const std::size_t b = *bodies.find(d.c.other_body);
      const auto* sb =
          std::get_if<engine::BoxShape>(&bodies.shapes()[bodies.shapesOf(b)[0]].geometry);
      std::printf("; b half (%.3f %.3f %.3f) type %d mass %.3f", sb->half_extents.x(),
                  sb->half_extents.y(), sb->half_extents.z(), (int)bodies.type(b), bodies.mass(b));
    }
    std::printf("\n");
    if (k == 0 && d.c.other == engine::BodyContactReport::Other::kBody) {
      const std::size_t b = *bodies.find(d.c.other_body);
      const auto box = [&](std::size_t i) {
        return std::get<engine::BoxShape>(bodies.shapes()[bodies.shapesOf(i)[0]].geometry)
            .half_extents;
      };
      // Deepest vertex of one box inside the other: min over the other's faces of the distance
      // inside.
      const auto deepest = [&](std::size_t i, std::size_t j) {
        const engine::Transform pi = bodies.pose(i), pj = bodies.pose(j);
        const Vec3 hi = box(i), hj = box(j);
        double best = -1;
        for (int c = 0; c < 8; ++c) {
          const Vec3 corner((c & 1 ? 1 : -1) * hi.x(), (c & 2 ? 1 : -1) * hi.y(),
                            (c & 4 ? 1 : -1) * hi.z());
          const Vec3 w = pi.apply(corner);
          const Vec3 l = pj.applyInverse(w);
          const Vec3 inside = hj - l.cwiseAbs();
          if ((inside.array() > 0).all()) best = std::max(best, inside.minCoeff());
        }
        return best;
      };
      std::printf("  independent: deepest vertex of a in b %.4f, of b in a %.4f\n", deepest(a, b),
                  deepest(b, a));
      {  // the separating axis test's least overlap, from the boxes alone
        const engine::Transform pa = bodies.pose(a), pb = bodies.pose(b);
        const engine::Mat3 ra = pa.rotation.toRotationMatrix(), rb = pb.rotation.toRotationMatrix();
        const Vec3 ha = box(a), hb = box(b);
        const Vec3 dcen = pb.position - pa.position;
        double best = 1e9;
        Vec3 best_axis = Vec3::Zero();
        int best_k = -1;
        std::vector<Vec3> axes;
        for (int i = 0; i < 3; ++i) axes.push_back(ra.col(i));
        for (int i = 0; i < 3; ++i) axes.push_back(rb.col(i));
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j) axes.push_back(ra.col(i).cross(rb.col(j)));
        for (int k = 0; k < (int)axes.size(); ++k) {
          Vec3 L = axes[k];
          if (L.norm() < 1e-9) continue;
          L.normalize();
          double rA = 0, rB = 0;
          for (int i = 0; i < 3; ++i) {
            rA += ha[i] * std::abs(ra.col(i).dot(L));
            rB += hb[i] * std::abs(rb.col(i).dot(L));
          }
          const double overlap = rA + rB - std::abs(dcen.dot(L));
          if (overlap < best) {
            best = overlap;
            best_axis = L;
            best_k = k;
          }
        }
        std::printf("  SAT: least overlap %.4f on axis %d (%.2f %.2f %.2f)\n", best, best_k,
                    best_axis.x(), best_axis.y(), best_axis.z());
      }
      if (getenv("NOGRAVITY")) {
        engine::WorldConfig c = world.config();
        c.gravity.setZero();
        world.setConfig(c);
        for (std::size_t i = 0; i < bodies.size(); ++i)
          if (bodies.dynamic(i)) world.setBodyVelocity(bodies.idAt(i), Vec3::Zero(), Vec3::Zero());
      }
      for (int extra = 0; extra < 120; ++extra) {
        world.step();
        if (extra % 20 == 0)
          for (const auto& c : world.bodyContacts())
            if (c.body == d.c.body && c.other_body == d.c.other_body) {
              double w = 0;
              for (const auto& p : c.points) w = std::max(w, -p.separation);
              std::printf("   step %d: %zu points deepest %.4f normal (%.2f %.2f %.2f)\n", extra,
                          c.points.size(), w, c.normal.x(), c.normal.y(), c.normal.z());
            }
      }
      for (const auto& c : world.bodyContacts()) {
        if (!(c.body == d.c.body && c.other_body == d.c.other_body)) continue;
        double w = 0;
        for (const auto& p : c.points) w = std::max(w, -p.separation);
        std::printf("  after 2 s more: %zu points, deepest %.4f\n", c.points.size(), w);
      }
    }
  }
}
