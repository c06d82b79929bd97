#pragma once
// What both rigid benchmark programs (rigid_bench.cpp: the engine, bullet_peer_bench.cpp: Bullet)
// report beside their timings, so that their tables compare column for column.

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <vector>

#include "rigid_scenes.h"

namespace mass_aggregate_sim {
namespace bench {
namespace rigid {

// The frames simulated untimed before a case is timed (10 s at 60 Hz); their mean cost is the
// settle_ms counter.
constexpr int kSettleFrames = 600;

// The last settle frames (3 s) whose deepest overlap is sampled every frame: a pile's deepest
// overlap at one instant swings with what its boxes are doing (the 1,000-box random drop's, at
// 4 x 10, went from 0.4 mm at 8 s to 4.3 mm at 9 s), so the worst and the mean over these frames
// are reported beside the last frame's.
constexpr int kLateFrames = 180;

// The settle: its frames' cost (stepping only, not the sampling), the late overlaps (m) and how
// many dynamic bodies moved more than 1 mm and 1 cm over those late frames (a pile at rest moves
// none; one that creeps or slides moves many).
struct Settled {
  double seconds = 0.0;
  double late_max_penetration = 0.0;
  double late_mean_penetration = 0.0;
  int late_moved_mm = 0;
  int late_moved_cm = 0;
  // Dynamic bodies whose last frame was free fall (nothing touched them), and the kinetic energy
  // of those that are neither in free fall nor escaped: what is left of the pile's motion. The
  // kinetic energy of every body can be mostly a few falling or runaway ones (at 10 s the rain's
  // spheres that rolled off the stack's top and those thrown over the walls).
  int in_flight = 0;
  double pile_kinetic_energy = 0.0;
};

// A body's velocity changed by gravity's alone over a frame to within this (m/s): any contact
// impulse changes it by far more than rounding does.
constexpr double kFreeFallTolerance = 1e-6;

// Steps `world` (stepFrame(), deepestOverlap(), and of the scene's body k position(k),
// linearVelocity(k) and kineticEnergy(k)) through the settle frames.
template <typename PeerWorld>
Settled settle(PeerWorld& world, const RigidScene& scene) {
  Settled settled;
  std::vector<Eigen::Vector3d> late_start;
  std::vector<Eigen::Vector3d> last_frame_velocity;
  for (int frame = 0; frame < kSettleFrames; ++frame) {
    if (frame == kSettleFrames - kLateFrames) {
      for (std::size_t k = 0; k < scene.bodies.size(); ++k) late_start.push_back(world.position(k));
    }
    if (frame == kSettleFrames - 1) {
      for (std::size_t k = 0; k < scene.bodies.size(); ++k) {
        last_frame_velocity.push_back(world.linearVelocity(k));
      }
    }
    const auto start = std::chrono::steady_clock::now();
    world.stepFrame();
    settled.seconds +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (frame >= kSettleFrames - kLateFrames) {
      const double deepest = world.deepestOverlap();
      settled.late_max_penetration = std::max(settled.late_max_penetration, deepest);
      settled.late_mean_penetration += deepest / kLateFrames;
    }
  }
  for (std::size_t k = 0; k < scene.bodies.size(); ++k) {
    if (scene.bodies[k].isFixed()) continue;
    const double moved = (world.position(k) - late_start[k]).norm();
    settled.late_moved_mm += moved > 1e-3 ? 1 : 0;
    settled.late_moved_cm += moved > 1e-2 ? 1 : 0;
    const Eigen::Vector3d change = world.linearVelocity(k) - last_frame_velocity[k];
    if ((change - scene.gravity * kFrameSeconds).norm() < kFreeFallTolerance) {
      ++settled.in_flight;
    } else if (!hasEscaped(scene, world.position(k))) {
      settled.pile_kinetic_energy += world.kineticEnergy(k);
    }
  }
  return settled;
}

// A scene's quality once those frames have run.
struct AtRest {
  double kinetic_energy = 0.0;  // J, of the dynamic bodies
  double top_drop = 0.0;        // start height minus height now, of the scene's top body
  double top_distance = 0.0;    // how far the top body is from where it started
  double max_penetration = 0.0;
  int contacts = 0;  // contact points
  int escaped = 0;   // dynamic bodies outside the walls or below the ground
  int asleep = 0;
};

inline void reportAtRest(benchmark::State& state, const RigidScene& scene, const AtRest& at_rest,
                         const Settled& settled) {
  const auto dynamic = std::count_if(scene.bodies.begin(), scene.bodies.end(),
                                     [](const BodySpec& body) { return !body.isFixed(); });
  state.counters["bodies"] = static_cast<double>(dynamic);
  state.counters["kinetic_J"] = at_rest.kinetic_energy;
  state.counters["max_pen_m"] = at_rest.max_penetration;
  state.counters["contacts"] = at_rest.contacts;
  state.counters["escaped"] = at_rest.escaped;
  state.counters["asleep"] = at_rest.asleep;
  if (scene.top_body >= 0) {
    state.counters["top_drop_m"] = at_rest.top_drop;
    state.counters["top_moved_m"] = at_rest.top_distance;
    state.counters["stood"] = at_rest.top_distance < kStoodTolerance ? 1.0 : 0.0;
  }
  state.counters["late_max_pen_m"] = settled.late_max_penetration;
  state.counters["late_mean_pen_m"] = settled.late_mean_penetration;
  state.counters["late_moved_mm"] = settled.late_moved_mm;
  state.counters["late_moved_cm"] = settled.late_moved_cm;
  state.counters["in_flight"] = settled.in_flight;
  state.counters["pile_kinetic_J"] = settled.pile_kinetic_energy;
  state.counters["settle_ms"] = 1e3 * settled.seconds / kSettleFrames;
}

}  // namespace rigid
}  // namespace bench
}  // namespace mass_aggregate_sim
