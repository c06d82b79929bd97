// Capsule against capsule: the closest points of the two segments, or two points when the
// segments lie side by side.
#include <algorithm>
#include <cstdint>

#include "engine/collision/narrowphase/contact_points.h"
#include "engine/collision/narrowphase/narrowphase.h"
#include "engine/collision/narrowphase/segment_closest.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

// Ids of the two-point manifold: which end bounds each point.
enum SideBySideFeature : std::uint32_t { kEndB0 = 1, kEndB1 = 2, kEndA0 = 3, kEndA1 = 4 };

// The normal when the segments meet: across both (the shortest way out), else across A's axis;
// oriented from A's centre towards B's.
Vec3 meetingNormal(const Segment& a, const Segment& b, const Frame& fa, const Frame& fb) {
  const Vec3 across = a.axis.cross(b.axis);
  const Real length = across.norm();
  const Vec3 n = length > kParallelSine * a.axis.norm() * b.axis.norm() && length > kTinyLength
                     ? Vec3(across / length)
                     : Vec3(fa.rotation.col(0));
  return n.dot(fb.position - fa.position) < 0.0 ? Vec3(-n) : n;
}

// B's segment clipped to the stretch beside A's (parallel segments): its ends become the points.
// Adds nothing when the stretches do not overlap.
void addSideBySide(const Segment& a, const Real ra, const Segment& b, const Real rb,
                   const Real margin, Manifold& manifold) {
  const Real length_a = a.axis.norm();
  const Real length_b = b.axis.norm();
  const Vec3 u = a.axis / length_a;
  // B's points b.start + w b.axis lie beside A where 0 <= along(w) <= length_a.
  const Real along_start = (b.start - a.start).dot(u);
  const Real slope = b.axis.dot(u);  // near +-length_b: the segments are parallel
  const Real w_at_a0 = -along_start / slope;
  const Real w_at_a1 = (length_a - along_start) / slope;
  const bool a0_first = w_at_a0 < w_at_a1;
  // An end of B less than the slack beyond A's end is kept (the same id while they jiggle).
  const Real slack = kClipSlack * std::min(length_a, length_b) / length_b;
  Real w[2] = {0.0, 1.0};
  std::uint32_t id[2] = {kEndB0, kEndB1};
  const Real enter = a0_first ? w_at_a0 : w_at_a1;
  const Real exit = a0_first ? w_at_a1 : w_at_a0;
  if (enter > w[0] + slack) {
    w[0] = enter;
    id[0] = a0_first ? kEndA0 : kEndA1;
  }
  if (exit < w[1] - slack) {
    w[1] = exit;
    id[1] = a0_first ? kEndA1 : kEndA0;
  }
  if (!((w[1] - w[0]) * length_b > kTinyLength)) return;
  for (int k = 0; k < 2; ++k) {
    const Vec3 qb = b.start + w[k] * b.axis;
    const Real s = std::clamp((qb - a.start).dot(u) / length_a, Real{0.0}, Real{1.0});
    const Vec3 qa = a.start + s * a.axis;
    const Real separation = (qb - qa).dot(manifold.normal) - ra - rb;
    if (separation <= margin) {
      addPoint(manifold, 0.5 * (qa + qb + (ra - rb) * manifold.normal), separation, id[k]);
    }
  }
}

}  // namespace

Manifold collide(const CapsuleShape& a, const Frame& fa, const CapsuleShape& b, const Frame& fb,
                 const Real margin) {
  Manifold manifold;
  const Segment sa = capsuleSegment(a, fa);
  const Segment sb = capsuleSegment(b, fb);
  const SegmentParameters st = closestSegmentParameters(sa.start, sa.axis, sb.start, sb.axis);
  const Vec3 qa = sa.start + st.s * sa.axis;
  const Vec3 qb = sb.start + st.t * sb.axis;
  const Vec3 d = qb - qa;
  const Real distance = d.norm();
  const Real separation = distance - a.radius - b.radius;
  if (!(separation <= margin)) return manifold;
  manifold.normal = distance > kTinyLength ? Vec3(d / distance) : meetingNormal(sa, sb, fa, fb);

  const Real length_a = sa.axis.norm();
  const Real length_b = sb.axis.norm();
  const bool parallel = length_a > kTinyLength && length_b > kTinyLength &&
                        sa.axis.cross(sb.axis).norm() <= kParallelSine * length_a * length_b;
  if (parallel) {
    addSideBySide(sa, a.radius, sb, b.radius, margin, manifold);
    if (manifold.count > 0) return manifold;
  }
  addPoint(manifold, 0.5 * (qa + qb + (a.radius - b.radius) * manifold.normal), separation, 0);
  return manifold;
}

}  // namespace engine
}  // namespace mass_aggregate_sim
