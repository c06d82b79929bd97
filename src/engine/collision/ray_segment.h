#pragma once

#include <algorithm>
#include <array>

#include "mass_aggregate_sim/engine/core/transform.h"

namespace mass_aggregate_sim {
namespace engine {

// The ray origin + t direction, t >= 0, with what the slab test against many boxes reuses.
class RaySegment {
 public:
  RaySegment(const Vec3& origin, const Vec3& direction) : origin_(origin) {
    for (int k = 0; k < 3; ++k) {
      // A zero component would make (lower - origin) * inf a NaN when the origin lies on the
      // slab's face: that axis is tested as a plain interval instead.
      parallel_[k] = direction[k] == 0.0;
      inverse_direction_[k] = parallel_[k] ? 0.0 : 1.0 / direction[k];
    }
  }

  // True when the segment t in [0, max_t] crosses the closed box; then entry is the smallest such
  // t. Rounding is monotone, so a box inside another never reports a hit the outer one misses.
  bool enters(const Aabb& box, const Real max_t, Real& entry) const {
    Real t_min = 0.0;
    Real t_max = max_t;
    for (int k = 0; k < 3; ++k) {
      if (parallel_[k]) {
        if (origin_[k] < box.lower[k] || origin_[k] > box.upper[k]) return false;
        continue;
      }
      const Real t1 = (box.lower[k] - origin_[k]) * inverse_direction_[k];
      const Real t2 = (box.upper[k] - origin_[k]) * inverse_direction_[k];
      t_min = std::max(t_min, std::min(t1, t2));
      t_max = std::min(t_max, std::max(t1, t2));
      if (t_min > t_max) return false;
    }
    entry = t_min;
    return true;
  }

 private:
  Vec3 origin_;
  Vec3 inverse_direction_;
  std::array<bool, 3> parallel_{};
};

}  // namespace engine
}  // namespace mass_aggregate_sim
