#include "engine/bodies/islands.h"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <vector>

#include "engine/core/union_find.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

// Calls f(dense a, dense b) when contact c links two bodies: shapes touching with a point.
template <typename F>
void contactLink(const BodyStore& bodies, const BodyContact& c, F&& f) {
  if (c.key.other != ContactOther::kShape || c.manifold.count == 0) return;
  const BodyShape& a = bodies.shapes()[c.key.shape];
  const BodyShape& b = bodies.shapes()[static_cast<ShapeIndex>(c.key.b)];
  if (!a.live || !b.live) return;
  f(bodies.denseIndexUnchecked(a.body), bodies.denseIndexUnchecked(b.body));
}

// Calls f(dense a, dense b) for every joint between two bodies.
template <typename F>
void jointLinks(const BodyStore& bodies, const Joints& joints, F&& f) {
  joints.forEach([&](const auto& kind) {
    for (const auto& joint : kind) {
      if (!joint.a.isBody() || !joint.b.isBody()) continue;
      const auto a = bodies.find(joint.a.body);
      const auto b = bodies.find(joint.b.body);
      if (a && b) f(*a, *b);
    }
  });
}

// Every link of the body graph: shape contacts with a point, and joints between two bodies.
template <typename F>
void forEachLink(const BodyStore& bodies, const BodyWorkspace& ws, const Joints& joints, F&& f) {
  for (const BodyContact& c : ws.contacts) contactLink(bodies, c, f);
  jointLinks(bodies, joints, f);
}

// The links with an awake side (ws.awake_contacts, and the joints): the others join two sleeping
// bodies, which neither wake anything nor change an awake island.
template <typename F>
void forEachAwakeLink(const BodyStore& bodies, const BodyWorkspace& ws, const Joints& joints,
                      F&& f) {
  for (const std::uint32_t c : ws.awake_contacts) contactLink(bodies, ws.contacts[c], f);
  jointLinks(bodies, joints, f);
}

// Fixed and kinematic bodies do not carry an island across them.
bool joins(const BodyStore& bodies, const std::size_t i) { return bodies.dynamic(i); }

}  // namespace

std::size_t countIslands(const BodyStore& bodies, const BodyWorkspace& ws, const Joints& joints) {
  UnionFind islands(bodies.size());
  forEachLink(bodies, ws, joints, [&](const std::size_t a, const std::size_t b) {
    if (joins(bodies, a) && joins(bodies, b)) islands.join(a, b);
  });
  std::size_t count = 0;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    if (bodies.dynamic(i) && islands.find(i) == i) ++count;
  }
  return count;
}

void wakeIslands(BodyStore& bodies, const BodyWorkspace& ws, const Joints& joints,
                 const std::vector<std::size_t>& seeds) {
  std::vector<std::size_t> sleeping;
  for (const std::size_t body : seeds) {
    if (bodies.dynamic(body) && !bodies.awake(body)) {
      sleeping.push_back(body);
    } else if (bodies.type(body) != BodyType::kFixed) {
      bodies.setAwake(body, true);
    }
  }
  if (sleeping.empty()) return;
  UnionFind islands(bodies.size());
  forEachLink(bodies, ws, joints, [&](const std::size_t a, const std::size_t b) {
    if (joins(bodies, a) && joins(bodies, b)) islands.join(a, b);
  });
  std::vector<std::uint8_t> woken(bodies.size(), 0);  // by island root
  for (const std::size_t body : sleeping) woken[islands.find(body)] = 1;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    if (bodies.dynamic(i) && woken[islands.find(i)]) bodies.setAwake(i, true);
  }
}

void wakeIsland(BodyStore& bodies, const BodyWorkspace& ws, const Joints& joints,
                const std::size_t body) {
  wakeIslands(bodies, ws, joints, {body});
}

bool wakeTouchedIslands(BodyStore& bodies, const BodyWorkspace& ws, const Joints& joints) {
  std::vector<std::size_t> to_wake;
  forEachAwakeLink(bodies, ws, joints, [&](const std::size_t a, const std::size_t b) {
    const bool moving_a = bodies.awake(a) && bodies.type(a) != BodyType::kFixed;
    const bool moving_b = bodies.awake(b) && bodies.type(b) != BodyType::kFixed;
    if (moving_a && bodies.dynamic(b) && !bodies.awake(b)) to_wake.push_back(b);
    if (moving_b && bodies.dynamic(a) && !bodies.awake(a)) to_wake.push_back(a);
  });
  wakeIslands(bodies, ws, joints, to_wake);
  return !to_wake.empty();
}

void updateSleep(BodyStore& bodies, const BodyWorkspace& ws, const Joints& joints,
                 const BodySettings& settings, const Real dt,
                 const std::vector<std::uint8_t>& busy) {
  const std::size_t n = bodies.size();
  // A body is slow when no point of it moves faster than sleep_speed: |v| + |w| reach.
  bool any_awake = false;
  for (std::size_t i = 0; i < n; ++i) {
    if (!bodies.dynamic(i) || !bodies.awake(i)) continue;
    any_awake = true;
    const Real speed =
        bodies.linearVelocity(i).norm() + bodies.angularVelocity(i).norm() * bodies.reach(i);
    const bool slow =
        bodies.canSleep(i) && speed < settings.sleep_speed && (i >= busy.size() || !busy[i]);
    bodies.sleepTime(i) = slow ? bodies.sleepTime(i) + dt : 0.0;
  }
  if (!settings.sleep || !any_awake) return;
  UnionFind islands(n);
  forEachAwakeLink(bodies, ws, joints, [&](const std::size_t a, const std::size_t b) {
    if (joins(bodies, a) && joins(bodies, b)) islands.join(a, b);
    // Touching a moving kinematic body keeps an island awake.
    if (bodies.type(a) == BodyType::kKinematic || bodies.type(b) == BodyType::kKinematic) {
      const std::size_t k = bodies.type(a) == BodyType::kKinematic ? a : b;
      const std::size_t other = k == a ? b : a;
      if (!bodies.linearVelocity(k).isZero(0.0) || !bodies.angularVelocity(k).isZero(0.0)) {
        bodies.sleepTime(other) = 0.0;
      }
    }
  });
  // The least slow time of each island.
  std::vector<Real> least(n, std::numeric_limits<Real>::infinity());
  for (std::size_t i = 0; i < n; ++i) {
    if (!bodies.dynamic(i) || !bodies.awake(i)) continue;
    const std::size_t root = islands.find(i);
    least[root] = std::min(least[root], bodies.sleepTime(i));
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (!bodies.dynamic(i) || !bodies.awake(i)) continue;
    // To the nearest step: thirty additions of 1/60 s fall a hair short of 0.5 s.
    if (least[islands.find(i)] < settings.time_to_sleep - 0.5 * dt) continue;
    bodies.setAwake(i, false);
    bodies.linearVelocity(i).setZero();
    bodies.angularVelocity(i).setZero();
  }
}

}  // namespace engine
}  // namespace mass_aggregate_sim
