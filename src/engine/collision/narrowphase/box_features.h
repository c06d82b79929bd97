#pragma once
// How the pair functions number a box's features (for the manifold points' ids) and find them.

#include <cstdint>

#include "mass_aggregate_sim/engine/core/types.h"

namespace mass_aggregate_sim {
namespace engine {

// Face with outward normal sign * e_axis: 2 axis + (sign < 0), 0..5.
inline std::uint32_t boxFaceIndex(const int axis, const Real sign) {
  return 2u * static_cast<std::uint32_t>(axis) + (sign < 0.0 ? 1u : 0u);
}

// Corner c (0..7): coordinate k is -h_k when bit k of c is set, else +h_k.
inline Vec3 boxCorner(const Vec3& h, const int c) {
  return Vec3((c & 1) ? -h.x() : h.x(), (c & 2) ? -h.y() : h.y(), (c & 4) ? -h.z() : h.z());
}

// An edge from start to start + axis, in the box's frame. index (0..11) = 4 k + 2 (its coordinate
// along the next axis is negative) + (its coordinate along the one after is negative), k the
// edge's direction.
struct BoxEdge {
  Vec3 start;
  Vec3 axis;
  std::uint32_t index;
};

// The edge along axis k farthest in the direction toward (ties: the positive side).
inline BoxEdge boxSupportEdge(const Vec3& h, const int k, const Vec3& toward) {
  const int u = (k + 1) % 3;
  const int v = (k + 2) % 3;
  const bool negative_u = toward[u] < 0.0;
  const bool negative_v = toward[v] < 0.0;
  BoxEdge edge;
  edge.start[k] = -h[k];
  edge.start[u] = negative_u ? -h[u] : h[u];
  edge.start[v] = negative_v ? -h[v] : h[v];
  edge.axis = Vec3::Zero();
  edge.axis[k] = 2.0 * h[k];
  edge.index = 4u * static_cast<std::uint32_t>(k) + (negative_u ? 2u : 0u) + (negative_v ? 1u : 0u);
  return edge;
}

}  // namespace engine
}  // namespace mass_aggregate_sim
