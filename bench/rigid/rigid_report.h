#pragma once
// What both rigid benchmark programs (rigid_bench.cpp: the engine, bullet_peer_bench.cpp: Bullet)
// report beside their timings, so that their tables compare column for column.

#include <benchmark/benchmark.h>

#include <algorithm>

#include "rigid_scenes.h"

namespace mass_aggregate_sim {
namespace bench {
namespace rigid {

// The frames simulated untimed before a case is timed (10 s at 60 Hz); their mean cost is the
// settle_ms counter.
constexpr int kSettleFrames = 600;

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
                         const double settle_seconds) {
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
  state.counters["settle_ms"] = 1e3 * settle_seconds / kSettleFrames;
}

}  // namespace rigid
}  // namespace bench
}  // namespace mass_aggregate_sim
