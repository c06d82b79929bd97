// Box against box: the separating-axis test over the 15 axes (each box's 3 face normals, the 9
// crossings of their edge directions), then either a face contact (the incident face clipped to
// the reference face) or one point between two edges. An edge pair whose axis lies within
// kNearFaceSine of a face normal is that face's contact.
//
// Ids: face contact = (reference is B) << 12 | reference face << 9 | incident face << 6 | clip
// code (face_clip.h), faces numbered by boxFaceIndex; edge contact = 1 << 13 | A's edge << 4 |
// B's edge, edges numbered by boxSupportEdge.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

#include "engine/collision/narrowphase/box_features.h"
#include "engine/collision/narrowphase/contact_points.h"
#include "engine/collision/narrowphase/face_clip.h"
#include "engine/collision/narrowphase/narrowphase.h"
#include "engine/collision/narrowphase/point_reduction.h"
#include "engine/collision/narrowphase/segment_closest.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

constexpr std::uint32_t kReferenceIsB = 1u << 12;
constexpr std::uint32_t kEdgeContact = 1u << 13;
// An edge of one box lying along the other's face, tilted by a hair, beats that face in the
// separating-axis test: the face axis overstates the overlap by the overhang (the edge's far end
// lies past the face's plane, beyond the face). The edge pair's one point then sits at one end of
// the stretch where the edge lies on the face and jumps to the other end when the tilt turns, so
// the box pivots about either end in turn. Up to this sine (0.29 degrees) the face decides: its
// clip gives both ends. A wider band (0.02) left piles livelier (docs/BENCHMARKS.md, session 21).
constexpr Real kNearFaceSine = 5e-3;

// The best (largest separation) axis of one family; direction in A's frame, from A towards B.
struct BestAxis {
  Real separation = -std::numeric_limits<Real>::infinity();
  int index = -1;
  Vec3 direction = Vec3::Zero();

  void consider(const Real s, const int i, const Vec3& d) {
    if (s > separation) {
      separation = s;
      index = i;
      direction = d;
    }
  }
};

// The incident box's face that faces the reference face (its outward normal most against the
// reference normal), clipped to the reference face; its points within margin, reduced to four.
// Works in the reference box's frame; the manifold's normal is the reference face's normal,
// pointing from the reference box towards the incident one.
Manifold faceContact(const Vec3& hr, const Frame& fr, const Vec3& hi, const Frame& fi,
                     const int axis, const Real margin, const std::uint32_t reference_flag) {
  Manifold manifold;
  const Mat3 relative = fr.rotation.transpose() * fi.rotation;  // incident axes, reference frame
  const Vec3 centre = fr.applyInverse(fi.position);
  const Real sign = centre[axis] >= 0.0 ? 1.0 : -1.0;
  // The reference normal in the incident frame; of near-equal axes the first (a box on its edge
  // keeps its incident face).
  const Vec3 against = sign * relative.row(axis).transpose();
  int k = 0;
  for (int i = 1; i < 3; ++i) {
    if (std::abs(against[i]) > std::abs(against[k]) + kFeatureTolerance) k = i;
  }
  const Real incident_sign = against[k] > 0.0 ? -1.0 : 1.0;

  // The incident face's corners, in order around it: (u, v) = (+, +), (-, +), (-, -), (+, -).
  ClipPolygon polygon;
  const int u = (k + 1) % 3;
  const int v = (k + 2) % 3;
  constexpr std::array<Real, 4> kU = {1.0, -1.0, -1.0, 1.0};
  constexpr std::array<Real, 4> kV = {1.0, 1.0, -1.0, -1.0};
  for (int i = 0; i < 4; ++i) {
    Vec3 corner;
    corner[k] = incident_sign * hi[k];
    corner[u] = kU[i] * hi[u];
    corner[v] = kV[i] * hi[v];
    ClipVertex& vertex = polygon.vertices[polygon.count++];
    vertex.x = relative * corner + centre;
    vertex.edges = {{static_cast<std::int8_t>((i + 3) % 4), static_cast<std::int8_t>(i)}};
    vertex.code = static_cast<std::uint32_t>(i);
  }
  clipToFaceSides(hr, axis, polygon);

  Vec3 normal = Vec3::Zero();
  normal[axis] = sign;
  manifold.normal = fr.rotation * normal;
  const std::uint32_t faces =
      reference_flag | boxFaceIndex(axis, sign) << 9 | boxFaceIndex(k, incident_sign) << 6;
  std::array<ManifoldPoint, 8> candidates;
  int count = 0;
  for (int i = 0; i < polygon.count; ++i) {
    const ClipVertex& vertex = polygon.vertices[i];
    const Real separation = sign * vertex.x[axis] - hr[axis];
    if (!(separation <= margin)) continue;
    // Midway between the incident point and its foot on the reference face.
    candidates[count++] = ManifoldPoint{fr.apply(vertex.x - 0.5 * separation * normal), separation,
                                        faces | vertex.code};
  }
  addReducedPoints(candidates.data(), count, manifold.normal, kFeatureTolerance * hr.minCoeff(),
                   manifold);
  return manifold;
}

// One point midway between A's edge along axis i and B's along axis j nearest each other.
Manifold edgeContact(const BoxShape& a, const Frame& fa, const BoxShape& b, const Frame& fb,
                     const Mat3& b_in_a, const int i, const int j, const Vec3& direction,
                     const Real margin) {
  Manifold manifold;
  const BoxEdge edge_a = boxSupportEdge(a.half_extents, i, direction);
  const BoxEdge edge_b = boxSupportEdge(b.half_extents, j, -(b_in_a.transpose() * direction));
  const Vec3 start_a = fa.apply(edge_a.start);
  const Vec3 axis_a = fa.rotation * edge_a.axis;
  const Vec3 start_b = fb.apply(edge_b.start);
  const Vec3 axis_b = fb.rotation * edge_b.axis;
  const SegmentParameters st = closestSegmentParameters(start_a, axis_a, start_b, axis_b);
  const Vec3 on_a = start_a + st.s * axis_a;
  const Vec3 on_b = start_b + st.t * axis_b;
  manifold.normal = fa.rotation * direction;
  const Real separation = (on_b - on_a).dot(manifold.normal);
  if (!(separation <= margin)) return manifold;
  addPoint(manifold, 0.5 * (on_a + on_b), separation,
           kEdgeContact | edge_a.index << 4 | edge_b.index);
  return manifold;
}

}  // namespace

Manifold collide(const BoxShape& a, const Frame& fa, const BoxShape& b, const Frame& fb,
                 const Real margin) {
  const Vec3& ha = a.half_extents;
  const Vec3& hb = b.half_extents;
  const Mat3 c = fa.rotation.transpose() * fb.rotation;  // column j: B's axis j in A's frame
  const Mat3 abs_c = c.cwiseAbs();
  const Vec3 t = fa.rotation.transpose() * (fb.position - fa.position);  // in A's frame
  const Vec3 t_b = c.transpose() * t;                                    // in B's frame
  // Along a unit axis L the boxes reach sum_k ha_k |L.a_k| and sum_k hb_k |L.b_k| from their
  // centres; they are separated by |t.L| less both reaches.
  BestAxis face_a;
  BestAxis face_b;
  BestAxis edge;
  for (int i = 0; i < 3; ++i) {
    const Real s = std::abs(t[i]) - (ha[i] + abs_c.row(i).dot(hb));
    if (s > margin) return Manifold{};
    face_a.consider(s, i, Vec3::Unit(i));
  }
  for (int j = 0; j < 3; ++j) {
    const Real s = std::abs(t_b[j]) - (abs_c.col(j).dot(ha) + hb[j]);
    if (s > margin) return Manifold{};
    face_b.consider(s, j, c.col(j));
  }
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      const Vec3 across = Vec3::Unit(i).cross(c.col(j));
      const Real length = across.norm();
      if (!(length > kEdgeParallelSine)) continue;
      Vec3 axis = across / length;
      if (t.dot(axis) < 0.0) axis = -axis;
      const Real s =
          t.dot(axis) - (ha.dot(axis.cwiseAbs()) + hb.dot((c.transpose() * axis).cwiseAbs()));
      if (s > margin) return Manifold{};
      edge.consider(s, 3 * i + j, axis);
    }
  }
  if (face_a.index < 0 || face_b.index < 0) return Manifold{};  // a non-finite frame: no axis
  const Real tolerance = kFeatureTolerance * std::min(ha.minCoeff(), hb.minCoeff());
  const bool reference_b = face_b.separation > face_a.separation + tolerance;
  const Real face_separation = reference_b ? face_b.separation : face_a.separation;
  const auto contactOnFaceOfA = [&](const int axis) {
    return faceContact(ha, fa, hb, fb, axis, margin, 0);
  };
  const auto contactOnFaceOfB = [&](const int axis) {
    Manifold manifold = faceContact(hb, fb, ha, fa, axis, margin, kReferenceIsB);
    manifold.normal = -manifold.normal;
    return manifold;
  };
  if (edge.index >= 0 && edge.separation > face_separation + tolerance) {
    int axis_a = 0;
    int axis_b = 0;
    const Real cosine_a = edge.direction.cwiseAbs().maxCoeff(&axis_a);
    const Real cosine_b = (c.transpose() * edge.direction).cwiseAbs().maxCoeff(&axis_b);
    if (std::max(cosine_a, cosine_b) >= std::sqrt(1.0 - kNearFaceSine * kNearFaceSine)) {
      const Manifold manifold =
          cosine_a >= cosine_b ? contactOnFaceOfA(axis_a) : contactOnFaceOfB(axis_b);
      if (manifold.count > 0) return manifold;
    }
    return edgeContact(a, fa, b, fb, c, edge.index / 3, edge.index % 3, edge.direction, margin);
  }
  return reference_b ? contactOnFaceOfB(face_b.index) : contactOnFaceOfA(face_a.index);
}

}  // namespace engine
}  // namespace mass_aggregate_sim
