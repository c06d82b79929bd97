#pragma once
// What the pair functions share: their tolerances, adding a point to a manifold, and the contact
// of two balls (sphere-sphere, sphere-capsule and capsule-capsule come down to it).

#include <cstdint>

#include "engine/collision/narrowphase/manifold.h"
#include "mass_aggregate_sim/engine/bodies/capsule_shape.h"

namespace mass_aggregate_sim {
namespace engine {

// Closer than this (m), two points give no direction and the pair's fallback normal is used.
constexpr Real kTinyLength = 1e-12;
// A capsule within this sine of parallel to another capsule or to a box face touches it along a
// segment: two points, so that it rests without rocking.
constexpr Real kParallelSine = 1e-2;
// A feature that crosses a clipping boundary by less than this fraction of the boundary's size
// (the reference face's half extent, the shorter capsule's length) is kept whole rather than cut,
// so that touching features keep their ids when the shapes jiggle (equal boxes stacked, capsules
// of equal length side by side). The point then lies at most that far beyond the other's edge.
constexpr Real kClipSlack = 1e-4;
// A box face is preferred to the other box's face, and a face to an edge pair, unless the other
// separates the shapes by more than this fraction of the smallest half extent: resting boxes keep
// their features instead of flipping between near-equal axes. Likewise for the incident face (on
// the cosines) and the deepest point of a reduction (of the reference face's half extent).
constexpr Real kFeatureTolerance = 1e-3;
// Cross products of edge directions shorter than this (sine of their angle) are skipped as axes:
// near-parallel edges give no direction, and the face axes already cover them.
constexpr Real kEdgeParallelSine = 1e-6;

inline void addPoint(Manifold& manifold, const Vec3& point, const Real separation,
                     const std::uint32_t id) {
  manifold.points[manifold.count++] = ManifoldPoint{point, separation, id};
}

// Balls at ca (radius ra) and cb (radius rb): one point midway between the surfaces ca + ra n and
// cb - rb n. fallback_normal is used when the centres coincide.
inline Manifold ballContact(const Vec3& ca, const Real ra, const Vec3& cb, const Real rb,
                            const Real margin, const Vec3& fallback_normal) {
  Manifold manifold;
  const Vec3 d = cb - ca;
  const Real distance = d.norm();
  const Real separation = distance - ra - rb;
  if (!(separation <= margin)) return manifold;
  manifold.normal = distance > kTinyLength ? Vec3(d / distance) : fallback_normal;
  addPoint(manifold, 0.5 * (ca + cb + (ra - rb) * manifold.normal), separation, 0);
  return manifold;
}

// A capsule's segment in world coordinates: from start (its end at local z = -half_length) to
// start + axis.
struct Segment {
  Vec3 start;
  Vec3 axis;
};
inline Segment capsuleSegment(const CapsuleShape& capsule, const Frame& frame) {
  const Vec3 half_axis = frame.rotation.col(2) * capsule.half_length;
  return Segment{frame.position - half_axis, 2.0 * half_axis};
}

}  // namespace engine
}  // namespace mass_aggregate_sim
