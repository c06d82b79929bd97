// Particles on bodies (docs/BENCHMARKS.md, 2026-11-28 session 25): the node's particle_rain
// scene (config/scenes/particle_rain.yaml) on the engine alone, 432 grains of 5 cm, 50 g, falling
// from 3-4 m onto a three-row pyramid of six 0.5 m boxes of 20 kg, 120 Hz, 10 s (argument: the
// seconds). Prints the median and p90 over the last 3 s of the grains' kinetic energy, how many
// grains moved more than 1 cm over those 3 s and how far all of them moved, the cost of a step
// (all, the first 3 s, the last 3 s), the grains' and boxes' kinetic energy at the end, how many
// grains touch a box, the deepest grain-box overlap over the last 3 s (worst and mean), how far
// the top box moved, and where the grains ended (by height, and over the pyramid's footprint).
// Build and run from the repository root after scripts/bench.sh has built
// the engine:
//   g++ -std=c++17 -O2 -I include -I /usr/include/eigen3 \
//     docs/benchmarks/grain_rain_probe.cpp -o /tmp/grain_rain_probe \
//     -L ~/mass_aggregate_sim_ws/devel/lib -lmass_aggregate_sim_engine \
//     -Wl,-rpath,$HOME/mass_aggregate_sim_ws/devel/lib
//   SEED=3 /tmp/grain_rain_probe 10   # the block's jitter (7, the scene's, by default)
//   LAID=2 /tmp/grain_rain_probe 10   # instead, LAID layers of 25 grains laid on the top box
//   SPACE=0.12                        # the laid grains this far apart (0.1 m: they touch)
//   NOPP=1                            # particle-particle collisions off
//   INTEG=n                           # the particle integrator (Integrator's order)
//   PRINTKE=1, WHERE=1, TRACK=grain   # each second's kinetic energy; the grains that moved;
//                                     # one grain's state and box contacts every 6 steps
// The session's variants were scratch builds of src/engine with two switches (not in the repo):
// NOLEAD (particles met where the integrator predicted them) and NOSWEPTP (particle-body contacts
// made where the pair starts).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

#include "mass_aggregate_sim/engine/world/world.h"
using namespace mass_aggregate_sim::engine;
int main(int argc, char** argv) {
  const int seconds = argc > 1 ? atoi(argv[1]) : 10;
  WorldConfig c;
  c.dt = 1.0 / 120.0;
  c.gravity = Vec3(0, 0, -9.81);
  if (getenv("INTEG")) c.integrator = static_cast<Integrator>(atoi(getenv("INTEG")));
  World world(c);
  CollisionSettings cs;
  cs.particle_collisions = !getenv("NOPP");
  cs.broadphase = Broadphase::kUniformGrid;
  cs.particle_restitution = 0.1;
  cs.particle_friction = 0.3;
  world.setCollisionSettings(cs);
  world.addCollider(PlaneCollider{Vec3::UnitZ(), 0.0, Material{0.1, 0.6}});
  std::mt19937 rng(getenv("SEED") ? atoi(getenv("SEED")) : 7);
  std::uniform_real_distribution<Real> j(-0.005, 0.005);
  if (getenv("LAID")) {
    // layers of grains laid on the top box (0.5 m square at z = 1.5) and the middle boxes' tops
    for (int k = 0; k < atoi(getenv("LAID")); ++k)
      for (int y = 0; y < 5; ++y)
        for (int x = 0; x < 5; ++x) {
          ParticleSpec p;
          const Real space = getenv("SPACE") ? atof(getenv("SPACE")) : 0.1;
          p.position = Vec3(space * (x - 2) + 0.05 * (k % 2) + j(rng),
                            space * (y - 2) + 0.05 * (k % 2) + j(rng), 1.551 + 0.0707 * k);
          p.inverse_mass = 20.0;
          p.radius = 0.05;
          world.addParticle(p);
        }
  } else
    for (int k = 0; k < 3; ++k)
      for (int y = 0; y < 12; ++y)
        for (int x = 0; x < 12; ++x) {
          ParticleSpec p;
          p.position = Vec3(-0.66 + 0.12 * x + j(rng), -0.66 + 0.12 * y + j(rng),
                            (getenv("Z0") ? atof(getenv("Z0")) : 3.0) + 0.12 * k + j(rng));
          p.inverse_mass = 20.0;
          p.radius = 0.05;
          world.addParticle(p);
        }
  const Vec3 pos[6] = {{-0.51, 0, 0.25},  {0, 0, 0.25},     {0.51, 0, 0.25},
                       {-0.255, 0, 0.75}, {0.255, 0, 0.75}, {0, 0, 1.25}};
  std::vector<BodyId> ids;
  for (const Vec3& q : pos) {
    BodySpec b;
    BodyShapeSpec s;
    s.geometry = BoxShape{Vec3::Constant(0.25)};
    s.material = Material{0.0, 0.6};
    b.shapes.push_back(s);
    b.mass = 20;
    b.pose.position = q;
    ids.push_back(*world.addBody(b));
  }
  double secs = 0, early = 0, last = 0;
  std::vector<double> late_ke;
  Eigen::Matrix<Real, 3, Eigen::Dynamic> late_start;
  double late_deep = 0, late_mean = 0;
  const int steps = seconds * 120, late = 3 * 120;
  for (int s = 0; s < steps; ++s) {
    auto t0 = std::chrono::steady_clock::now();
    world.step();
    const double dt_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    secs += dt_;
    if (s < 360) early += dt_;
    if (s >= steps - late) last += dt_;
    if (getenv("PRINTKE") && (s + 1) % 120 == 0) {
      const auto vv = world.particles().velocities();
      double ke = 0, vmax = 0;
      Eigen::Index im = 0;
      for (Eigen::Index i = 0; i < vv.cols(); ++i) {
        ke += 0.025 * vv.col(i).squaredNorm();
        if (vv.col(i).norm() > vmax) {
          vmax = vv.col(i).norm();
          im = i;
        }
      }
      const Vec3 xm = world.particles().positions().col(im);
      std::printf("  t %d s: grain KE %.3e, fastest %.3f m/s at (%.3f %.3f %.3f)\n", (s + 1) / 120,
                  ke, vmax, xm.x(), xm.y(), xm.z());
    }
    if (getenv("TRACK") && s >= steps - late && (s % 6 == 0)) {
      const long g = atol(getenv("TRACK"));
      const auto xx = world.particles().positions();
      const auto vv = world.particles().velocities();
      std::printf("  s %d grain %ld x (%.4f %.4f %.4f) v (%.4f %.4f %.4f)", s, g, xx(0, g),
                  xx(1, g), xx(2, g), vv(0, g), vv(1, g), vv(2, g));
      for (const auto& r : world.bodyContacts())
        if (r.other == BodyContactReport::Other::kParticle &&
            r.particle == world.particles().idAt(g))
          for (const auto& p : r.points)
            std::printf(" | n (%.2f %.2f %.2f) sep %.5f j %.2e f (%.1e %.1e %.1e)", r.normal.x(),
                        r.normal.y(), r.normal.z(), p.separation, p.normal_impulse,
                        p.friction_impulse.x(), p.friction_impulse.y(), p.friction_impulse.z());
      std::printf("\n");
    }
    if (s >= steps - late) {
      {
        const auto vv = world.particles().velocities();
        double ke = 0;
        for (Eigen::Index i = 0; i < vv.cols(); ++i) ke += 0.025 * vv.col(i).squaredNorm();
        late_ke.push_back(ke);
      }
      if (s == steps - late) late_start = world.particles().positions();
      double d = 0;
      for (const auto& r : world.bodyContacts())
        if (r.other == BodyContactReport::Other::kParticle)
          for (const auto& p : r.points) d = std::max(d, -p.separation);
      late_deep = std::max(late_deep, d);
      late_mean += d / late;
    }
  }
  double grain_ke = 0;
  int on_boxes = 0;
  const auto v = world.particles().velocities();
  const auto x = world.particles().positions();
  for (Eigen::Index i = 0; i < v.cols(); ++i) {
    grain_ke += 0.5 * 0.05 * v.col(i).squaredNorm();
  }
  for (const auto& r : world.bodyContacts())
    if (r.other == BodyContactReport::Other::kParticle) ++on_boxes;
  double box_ke = 0,
         top_moved = (world.bodies().position(*world.bodies().find(ids[5])) - pos[5]).norm();
  for (BodyId id : ids) {
    const std::size_t i = *world.bodies().find(id);
    box_ke += 0.5 * 20 * world.bodies().linearVelocity(i).squaredNorm();
  }
  std::sort(late_ke.begin(), late_ke.end());
  int moved_cm = 0;
  double total_moved = 0;
  {
    const auto xx = world.particles().positions();
    for (Eigen::Index i = 0; i < xx.cols(); ++i) {
      total_moved += (xx.col(i) - late_start.col(i)).norm();
      const bool m = (xx.col(i) - late_start.col(i)).norm() > 0.01;
      moved_cm += m;
      if (m && getenv("WHERE"))
        std::printf("    moved grain %ld: from (%.3f %.3f %.3f) to (%.3f %.3f %.3f)\n", (long)i,
                    late_start(0, i), late_start(1, i), late_start(2, i), xx(0, i), xx(1, i),
                    xx(2, i));
    }
  }
  std::printf(
      "late KE median %.2e p90 %.2e, grains moved > 1 cm in the last 3 s %d total %.3f m | ",
      late_ke[late_ke.size() / 2], late_ke[late_ke.size() * 9 / 10], moved_cm, total_moved);
  std::printf(
      "%.3f ms/step (first 3 s %.3f, last 3 s %.3f)  grain KE %.3e J  box KE %.3e J  grains on "
      "boxes %d  late deepest grain-box %.2f mm mean %.3f mm  top moved %.2f mm\n",
      1e3 * secs / steps, 1e3 * early / 360, 1e3 * last / late, grain_ke, box_ke, on_boxes,
      1e3 * late_deep, 1e3 * late_mean, 1e3 * top_moved);
  // Where the grains ended: by height (the pyramid's rows of 0.5 m boxes), and over its footprint.
  const auto xx = world.particles().positions();
  int band[5] = {0, 0, 0, 0, 0};
  int over = 0;
  for (Eigen::Index i = 0; i < xx.cols(); ++i) {
    const double z = xx(2, i);
    ++band[z < 0.3 ? 0 : z < 0.8 ? 1 : z < 1.3 ? 2 : z < 1.8 ? 3 : 4];
    over += std::abs(xx(0, i)) < 0.76 && std::abs(xx(1, i)) < 0.3;
  }
  std::printf(
      "grains at z < 0.3 m %d, 0.3-0.8 %d, 0.8-1.3 %d, 1.3-1.8 %d, above %d; over the "
      "pyramid's footprint %d\n",
      band[0], band[1], band[2], band[3], band[4], over);
}
