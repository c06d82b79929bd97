#pragma once
// Small geometric routines the shape kinds share.

#include <algorithm>
#include <cmath>
#include <optional>

#include "mass_aggregate_sim/engine/collision/shape_kind.h"

namespace mass_aggregate_sim {
namespace engine {

// Closest point to x on the segment a-b.
inline Vec3 closestOnSegment(const Vec3& x, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const Real length_squared = ab.squaredNorm();
  if (length_squared <= 0.0) return a;
  const Real t = std::clamp((x - a).dot(ab) / length_squared, Real{0.0}, Real{1.0});
  return a + t * ab;
}

// Whether a point at squared distance d2 is certainly farther than reach, found without the
// square root: the bound is widened by 1e-9 of itself, far more than the rounding of sqrt and of
// reach - sqrt(d2), so it rejects only what the exact test `reach - sqrt(d2) > 0` rejects. Most
// particles are far from most colliders, and the square root's latency was a fifth of a box test.
inline bool certainlyBeyond(const Real squared_distance, const Real reach) {
  const Real widened = reach * (1.0 + 1e-9);
  return reach > 0.0 && squared_distance > widened * widened;
}

// The sphere at x of radius r against a ball at center of the given radius (normal from the
// ball towards x; concentric: up).
std::optional<ShapeContact> sphereAgainstBall(const Vec3& x, Real r, const Vec3& center,
                                              Real radius, Real margin);

// First entry of the ray origin + t direction (unit direction), t in [0, max_t], into the ball;
// none when it starts inside.
std::optional<RayShapeHit> rayIntoBall(const Vec3& origin, const Vec3& direction, Real max_t,
                                       const Vec3& center, Real radius);

// First entry of the ray (unit direction) into the box |x_k| <= h_k about the origin, all in the
// box's frame; none when it starts inside.
std::optional<RayShapeHit> rayIntoCentredBox(const Vec3& origin, const Vec3& direction, Real max_t,
                                             const Vec3& h);

// First entry of the ray (unit direction) into the capsule of the given radius around the segment
// a-b; none when it starts inside.
std::optional<RayShapeHit> rayIntoCapsule(const Vec3& origin, const Vec3& direction, Real max_t,
                                          const Vec3& a, const Vec3& b, Real radius);

// The earlier of two hits (either may be missing).
inline std::optional<RayShapeHit> earlier(const std::optional<RayShapeHit>& x,
                                          const std::optional<RayShapeHit>& y) {
  if (!x) return y;
  if (!y) return x;
  return y->t < x->t ? y : x;
}

// Earliest time s in [0, 1] at which two spheres moving linearly touch: |d0 + s dd| = sum of
// radii, with d0 the start offset of a from b and dd the relative displacement over the step.
// Nothing when they are already overlapping at the start or never touch.
std::optional<Real> sweptSpheresTimeOfImpact(const Vec3& d0, const Vec3& dd, Real radius_sum);

// The material checks every collider makes.
Status checkMaterial(const Material& material);

}  // namespace engine
}  // namespace mass_aggregate_sim
