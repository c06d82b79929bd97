#pragma once
// Closest points of two segments.

#include "mass_aggregate_sim/engine/core/types.h"

namespace mass_aggregate_sim {
namespace engine {

// The parameters s, t in [0, 1] of the closest points p1 + s d1 and p2 + t d2 of two segments.
// Parallel segments (many closest pairs) give the pair nearest s = 0; a zero-length segment is
// its start point.
struct SegmentParameters {
  Real s = 0.0;
  Real t = 0.0;
};
SegmentParameters closestSegmentParameters(const Vec3& p1, const Vec3& d1, const Vec3& p2,
                                           const Vec3& d2);

}  // namespace engine
}  // namespace mass_aggregate_sim
