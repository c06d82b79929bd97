#pragma once
// What the narrowphase tests share: frames, and checks of a manifold's normal, points and ids.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "engine/collision/narrowphase/pair_table.h"

namespace mass_aggregate_sim {
namespace engine {
namespace narrowphase_test {

constexpr Real kTolerance = 1e-12;

inline Quat about(const Vec3& axis, const Real angle) {
  return Quat(Eigen::AngleAxisd(angle, axis.normalized()));
}
inline Frame frameAt(const Vec3& position, const Quat& rotation = Quat::Identity()) {
  return Frame(Transform{position, rotation});
}
// Rotations that turn a capsule's local z onto world x and onto world y.
inline Quat zToX() { return about(Vec3::UnitY(), M_PI / 2); }
inline Quat zToY() { return about(Vec3::UnitX(), -M_PI / 2); }

// The frame moved by a rigid motion (both frames of a pair moved alike move the whole contact).
inline Frame moved(const Frame& motion, const Frame& frame) {
  return Frame(motion.apply(frame.position), motion.rotation * frame.rotation);
}
// A small turn (about axis) and shift, for the ids' stability.
inline Frame nudged(const Frame& frame, const Real amount = 1e-6,
                    const Vec3& axis = Vec3(0.3, -0.5, 0.8)) {
  const Frame nudge(Vec3(amount, -amount, 0.5 * amount), about(axis, amount).toRotationMatrix());
  return Frame(frame.position + nudge.position, nudge.rotation * frame.rotation);
}

struct Expected {
  Vec3 point;
  Real separation;
};

inline void expectNormal(const Manifold& m, const Vec3& normal, const Real tolerance = kTolerance) {
  EXPECT_TRUE((m.normal - normal).norm() <= tolerance)
      << "normal " << m.normal.transpose() << ", expected " << normal.transpose();
}

// The manifold has exactly these points, in any order.
inline void expectPoints(const Manifold& m, const std::vector<Expected>& expected,
                         const Real tolerance = kTolerance) {
  ASSERT_EQ(m.count, static_cast<int>(expected.size()));
  std::vector<bool> used(m.count, false);
  for (const Expected& e : expected) {
    int match = -1;
    for (int i = 0; i < m.count; ++i) {
      if (!used[i] && (m.points[i].point - e.point).norm() <= tolerance) match = i;
    }
    ASSERT_GE(match, 0) << "no point at " << e.point.transpose();
    used[match] = true;
    EXPECT_NEAR(m.points[match].separation, e.separation, tolerance) << e.point.transpose();
  }
}

inline std::vector<std::uint32_t> sortedIds(const Manifold& m) {
  std::vector<std::uint32_t> ids;
  for (int i = 0; i < m.count; ++i) ids.push_back(m.points[i].id);
  std::sort(ids.begin(), ids.end());
  return ids;
}

inline void expectDistinctIds(const Manifold& m) {
  const std::vector<std::uint32_t> ids = sortedIds(m);
  EXPECT_TRUE(std::adjacent_find(ids.begin(), ids.end()) == ids.end());
}

inline bool finiteUnitNormal(const Manifold& m) {
  if (!m.normal.allFinite() || std::abs(m.normal.norm() - 1.0) > 1e-12) return false;
  for (int i = 0; i < m.count; ++i) {
    if (!m.points[i].point.allFinite() || !std::isfinite(m.points[i].separation)) return false;
  }
  return true;
}

// The same contact seen after moving both shapes by motion: the normal and points moved, the
// separations and ids unchanged.
inline void expectMovesWith(const Manifold& before, const Manifold& after, const Frame& motion) {
  ASSERT_EQ(after.count, before.count);
  expectNormal(after, motion.rotation * before.normal, 1e-12);
  for (int i = 0; i < before.count; ++i) {
    EXPECT_LE((after.points[i].point - motion.apply(before.points[i].point)).norm(), 1e-12);
    EXPECT_NEAR(after.points[i].separation, before.points[i].separation, 1e-12);
    EXPECT_EQ(after.points[i].id, before.points[i].id);
  }
}

// A rigid motion with no special axes.
inline Frame someMotion() {
  return Frame(Vec3(3.0, -1.5, 0.7), about(Vec3(1.0, 2.0, -0.5), 0.9).toRotationMatrix());
}

}  // namespace narrowphase_test
}  // namespace engine
}  // namespace mass_aggregate_sim
