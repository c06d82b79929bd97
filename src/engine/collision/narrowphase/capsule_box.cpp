// Capsule against box, worked in the box's frame on the capsule's segment p0 + t d, t in [0, 1].
// Apart: the segment's nearest point to the box gives the normal, and a capsule lying along the
// nearest face gets two points. Meeting: a separating-axis test finds the shortest way out.
//
// Ids: 0 near an edge or corner; 1 + (face << 3 | feature) on face `face` (box_features.h), the
// feature being the capsule end (0, 1) or the side plane that cut the segment (2 + 2 j + (plane
// at -h_j)); 64 + edge index for the segment against a box edge.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>

#include "engine/collision/narrowphase/box_features.h"
#include "engine/collision/narrowphase/contact_points.h"
#include "engine/collision/narrowphase/narrowphase.h"
#include "engine/collision/narrowphase/segment_closest.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

constexpr std::uint32_t kEdgeIds = 64;

Vec3 clampToBox(const Vec3& x, const Vec3& h) { return x.cwiseMax(-h).cwiseMin(h); }

// The parameter of the segment's point nearest the box (the first of several). The squared
// distance f(t) = sum_k max(|p0_k + t d_k| - h_k, 0)^2 is convex and, between the parameters
// where the segment crosses a face plane, one quadratic; on each such piece its minimum is where
// sum over the axes outside of d_k (p0_k + t d_k - (+-h_k)) = 0, clamped to the piece.
Real nearestParameter(const Vec3& p0, const Vec3& d, const Vec3& h) {
  std::array<Real, 8> cuts;
  int count = 0;
  cuts[count++] = 0.0;
  for (int k = 0; k < 3; ++k) {
    if (d[k] == 0.0) continue;
    for (const Real side : {-1.0, 1.0}) {
      const Real t = (side * h[k] - p0[k]) / d[k];
      if (t > 0.0 && t < 1.0) cuts[count++] = t;
    }
  }
  cuts[count++] = 1.0;
  for (int i = 1; i < count; ++i) {  // insertion sort of at most 8
    for (int j = i; j > 0 && cuts[j] < cuts[j - 1]; --j) std::swap(cuts[j], cuts[j - 1]);
  }
  Real best_t = 0.0;
  Real best_f = std::numeric_limits<Real>::infinity();
  for (int i = 0; i + 1 < count; ++i) {
    const Real lo = cuts[i];
    const Real hi = cuts[i + 1];
    const Vec3 middle = p0 + 0.5 * (lo + hi) * d;
    Real numerator = 0.0;
    Real denominator = 0.0;
    for (int k = 0; k < 3; ++k) {
      if (std::abs(middle[k]) <= h[k]) continue;
      const Real target = middle[k] > 0.0 ? h[k] : -h[k];
      numerator += d[k] * (p0[k] - target);
      denominator += d[k] * d[k];
    }
    const Real t = denominator > 0.0 ? std::clamp(-numerator / denominator, lo, hi) : lo;
    const Vec3 x = p0 + t * d;
    const Real f = (x - clampToBox(x, h)).squaredNorm();
    if (f < best_f) {
      best_f = f;
      best_t = t;
    }
  }
  return best_t;
}

bool alongFace(const Vec3& d, const int axis) {
  const Real length = d.norm();
  return length > kTinyLength && std::abs(d[axis]) <= kParallelSine * length;
}

// The capsule lying along face (axis k, outward sign): its segment clipped to the face's side
// planes |x_j| <= h_j, and a point at each end of what is left. The surfaces there: the capsule's
// at s - r o, the face's at s - (separation + r) o. False when nothing is left.
bool addAlongFace(const Vec3& p0, const Vec3& d, const Real r, const Vec3& h, const int k,
                  const Real sign, const Frame& fb, const Real margin, Manifold& manifold) {
  Real t[2] = {0.0, 1.0};
  std::uint32_t feature[2] = {0, 1};
  for (int j = 0; j < 3; ++j) {
    if (j == k) continue;
    const Real slack = kClipSlack * h[j];
    if (d[j] == 0.0) {
      if (std::abs(p0[j]) > h[j] + slack) return false;
      continue;
    }
    // The segment is within the slab -h_j <= x_j <= h_j between these parameters; an end less
    // than slack outside it is kept.
    const Real at_minus = (-h[j] - p0[j]) / d[j];
    const Real at_plus = (h[j] - p0[j]) / d[j];
    const bool minus_first = at_minus < at_plus;
    const Real enter = minus_first ? at_minus : at_plus;
    const Real exit = minus_first ? at_plus : at_minus;
    const Real slack_t = slack / std::abs(d[j]);
    if (t[0] < enter - slack_t) {
      t[0] = enter;
      feature[0] = 2 + 2 * j + (minus_first ? 1 : 0);
    }
    if (t[1] > exit + slack_t) {
      t[1] = exit;
      feature[1] = 2 + 2 * j + (minus_first ? 0 : 1);
    }
  }
  if (!((t[1] - t[0]) * d.norm() > kTinyLength)) return false;
  Vec3 o = Vec3::Zero();
  o[k] = sign;
  const std::uint32_t face = boxFaceIndex(k, sign);
  const int before = manifold.count;
  for (int e = 0; e < 2; ++e) {
    const Vec3 s = p0 + t[e] * d;
    const Real separation = sign * s[k] - h[k] - r;
    if (separation <= margin) {
      addPoint(manifold, fb.apply(s - (r + 0.5 * separation) * o), separation,
               1 + (face << 3 | feature[e]));
    }
  }
  return manifold.count > before;
}

// The segment meets the box. The box swept along the segment is a polytope whose face normals are
// the box's face normals and the crossings of the segment with the box's edge directions; the
// least overlap over those axes is the segment's shortest way out, and the capsule's is r more.
Manifold meeting(const Vec3& p0, const Vec3& d, const Real r, const Vec3& h, const Frame& fb,
                 const Real margin) {
  Manifold manifold;
  const Vec3 centre = p0 + 0.5 * d;
  const Vec3 half = 0.5 * d;
  const Real length = d.norm();
  int face_axis = 0;
  Real face_overlap = std::numeric_limits<Real>::infinity();
  for (int k = 0; k < 3; ++k) {
    const Real overlap = h[k] + std::abs(half[k]) - std::abs(centre[k]);
    if (overlap < face_overlap) {
      face_overlap = overlap;
      face_axis = k;
    }
  }
  int edge_axis = -1;
  Real edge_overlap = std::numeric_limits<Real>::infinity();
  Vec3 edge_direction = Vec3::Zero();
  for (int j = 0; j < 3; ++j) {
    const Vec3 across = d.cross(Vec3::Unit(j));
    const Real across_length = across.norm();
    if (!(across_length > kEdgeParallelSine * length) || !(across_length > kTinyLength)) continue;
    const Vec3 axis = across / across_length;
    const Real overlap = h.dot(axis.cwiseAbs()) - std::abs(centre.dot(axis));
    if (overlap < edge_overlap) {
      edge_overlap = overlap;
      edge_axis = j;
      edge_direction = axis;
    }
  }
  const Real tolerance = kFeatureTolerance * h.minCoeff();
  if (edge_axis >= 0 && edge_overlap < face_overlap - tolerance) {
    const Vec3 o = centre.dot(edge_direction) >= 0.0 ? edge_direction : Vec3(-edge_direction);
    const Real separation = -edge_overlap - r;
    if (!(separation <= margin)) return manifold;
    const BoxEdge edge = boxSupportEdge(h, edge_axis, o);
    const SegmentParameters st = closestSegmentParameters(p0, d, edge.start, edge.axis);
    const Vec3 on_segment = p0 + st.s * d;
    const Vec3 on_edge = edge.start + st.t * edge.axis;
    manifold.normal = fb.rotation * (-o);
    addPoint(manifold, fb.apply(0.5 * (on_segment - r * o + on_edge)), separation,
             kEdgeIds + edge.index);
    return manifold;
  }
  const Real sign = centre[face_axis] >= 0.0 ? 1.0 : -1.0;
  const Real separation = -face_overlap - r;
  if (!(separation <= margin)) return manifold;
  Vec3 o = Vec3::Zero();
  o[face_axis] = sign;
  manifold.normal = fb.rotation * (-o);
  if (alongFace(d, face_axis) && addAlongFace(p0, d, r, h, face_axis, sign, fb, margin, manifold)) {
    return manifold;
  }
  // The deepest end.
  const std::uint32_t end = sign * d[face_axis] < 0.0 ? 1 : 0;
  const Vec3 s = p0 + static_cast<Real>(end) * d;
  addPoint(manifold, fb.apply(s - (r + 0.5 * separation) * o), separation,
           1 + (boxFaceIndex(face_axis, sign) << 3 | end));
  return manifold;
}

}  // namespace

Manifold collide(const CapsuleShape& a, const Frame& fa, const BoxShape& b, const Frame& fb,
                 const Real margin) {
  const Vec3& h = b.half_extents;
  const Real r = a.radius;
  const Segment segment = capsuleSegment(a, fa);
  const Vec3 p0 = fb.applyInverse(segment.start);
  const Vec3 d = fb.rotation.transpose() * segment.axis;
  const Real t = nearestParameter(p0, d, h);
  const Vec3 s = p0 + t * d;
  const Vec3 q = clampToBox(s, h);
  const Real distance = (s - q).norm();
  if (!(distance > kTinyLength)) return meeting(p0, d, r, h, fb, margin);

  Manifold manifold;
  const Real separation = distance - r;
  if (!(separation <= margin)) return manifold;
  const Vec3 o = (s - q) / distance;  // the box's outward normal towards the capsule
  manifold.normal = fb.rotation * (-o);
  int outside = 0;
  int face_axis = 0;
  for (int k = 0; k < 3; ++k) {
    if (s[k] != q[k]) {
      ++outside;
      face_axis = k;
    }
  }
  if (outside != 1) {
    // Nearest an edge or a corner. Surfaces at q and s - r o = q + (distance - r) o.
    addPoint(manifold, fb.apply(q + 0.5 * separation * o), separation, 0);
    return manifold;
  }
  const Real sign = o[face_axis];
  if (alongFace(d, face_axis) && addAlongFace(p0, d, r, h, face_axis, sign, fb, margin, manifold)) {
    return manifold;
  }
  // Nearest a face and not along it: the nearest point is an end.
  const std::uint32_t end = t < 0.5 ? 0 : 1;
  addPoint(manifold, fb.apply(q + 0.5 * separation * o), separation,
           1 + (boxFaceIndex(face_axis, sign) << 3 | end));
  return manifold;
}

}  // namespace engine
}  // namespace mass_aggregate_sim
