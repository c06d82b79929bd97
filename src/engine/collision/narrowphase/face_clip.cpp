#include "engine/collision/narrowphase/face_clip.h"

#include <cmath>

#include "engine/collision/narrowphase/contact_points.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

bool has(const std::array<std::int8_t, 2>& set, const std::int8_t value) {
  return value >= 0 && (set[0] == value || set[1] == value);
}

// The feature shared by two vertices: an incident edge, else a side plane; -1 when none.
std::int8_t sharedOf(const std::array<std::int8_t, 2>& a, const std::array<std::int8_t, 2>& b) {
  if (has(b, a[0])) return a[0];
  if (has(b, a[1])) return a[1];
  return -1;
}

// Where the polygon's side from p to q crosses plane `plane` (distances dp, dq of opposite signs).
ClipVertex crossing(const ClipVertex& p, const ClipVertex& q, const Real dp, const Real dq,
                    const int plane, const int axis, const Real at) {
  ClipVertex x;
  x.x = p.x + (q.x - p.x) * (dp / (dp - dq));
  x.x[axis] = at;  // exactly on the plane
  const std::int8_t edge = sharedOf(p.edges, q.edges);
  const auto plane_id = static_cast<std::int8_t>(plane);
  if (edge >= 0) {
    x.edges = {{edge, -1}};
    x.planes = {{plane_id, -1}};
    x.code = 4 + 4 * static_cast<std::uint32_t>(edge) + plane;
  } else {
    // The side runs along an earlier plane: x is a corner of the reference face.
    const std::int8_t along = sharedOf(p.planes, q.planes);
    x.planes = {{along, plane_id}};
    x.code = along >= 0 ? 20 + 4 * static_cast<std::uint32_t>(along) + plane : 63;
  }
  return x;
}

void clipAgainst(const int plane, const int axis, const Real sign, const Real h,
                 ClipPolygon& polygon) {
  ClipPolygon out;
  const int n = polygon.count;
  for (int i = 0; i < n; ++i) {
    const ClipVertex& p = polygon.vertices[i];
    const ClipVertex& q = polygon.vertices[(i + 1) % n];
    const Real dp = sign * p.x[axis] - h;
    const Real dq = sign * q.x[axis] - h;
    if (dp <= 0.0) out.vertices[out.count++] = p;
    if ((dp < 0.0 && dq > 0.0) || (dp > 0.0 && dq < 0.0)) {
      out.vertices[out.count++] = crossing(p, q, dp, dq, plane, axis, sign * h);
    }
  }
  polygon = out;
}

}  // namespace

void clipToFaceSides(const Vec3& h, const int axis, ClipPolygon& polygon) {
  const int u = (axis + 1) % 3;
  const int v = (axis + 2) % 3;
  for (int i = 0; i < polygon.count; ++i) {
    Vec3& x = polygon.vertices[i].x;
    for (const int w : {u, v}) {
      const Real beyond = std::abs(x[w]) - h[w];
      if (beyond > 0.0 && beyond <= kClipSlack * h[w]) x[w] = x[w] > 0.0 ? h[w] : -h[w];
    }
  }
  clipAgainst(0, u, 1.0, h[u], polygon);
  clipAgainst(1, u, -1.0, h[u], polygon);
  clipAgainst(2, v, 1.0, h[v], polygon);
  clipAgainst(3, v, -1.0, h[v], polygon);
}

}  // namespace engine
}  // namespace mass_aggregate_sim
