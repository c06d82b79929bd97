#pragma once

#include <optional>

#include "mass_aggregate_sim/engine/colliders.h"
#include "mass_aggregate_sim/engine/types.h"

namespace mass_aggregate_sim {
namespace engine {

// Overlap of a sphere (a particle) with a collider: moving the sphere by penetration along normal
// separates them.
struct ShapeContact {
  Vec3 normal;
  Real penetration;
};

// Each returns nothing when the sphere at x with radius r is farther than margin from the shape
// (penetration <= -margin); a contact with negative penetration is a gap about to close.
// Planes and boxes are solid: a sphere inside is pushed out by the nearest way.
std::optional<ShapeContact> sphereVsPlane(const Vec3& x, Real r, const PlaneCollider& plane,
                                          Real margin = 0.0);
std::optional<ShapeContact> sphereVsSphere(const Vec3& x, Real r, const Vec3& center, Real radius,
                                           Real margin = 0.0);
std::optional<ShapeContact> sphereVsBox(const Vec3& x, Real r, const BoxCollider& box,
                                        Real margin = 0.0);
std::optional<ShapeContact> sphereVsCapsule(const Vec3& x, Real r, const CapsuleCollider& capsule,
                                            Real margin = 0.0);

// First crossing of the ray origin + t direction (direction of unit length), t in [0, max_t],
// into a shape grown by `inflate` (the radius of a swept sphere; 0 for a plain ray). A ray that
// starts inside the (grown) shape does not hit it.
struct RayShapeHit {
  Real t;
  Vec3 normal;  // outward normal of the shape at the hit
};
std::optional<RayShapeHit> rayVsPlane(const Vec3& origin, const Vec3& direction, Real max_t,
                                      const PlaneCollider& plane, Real inflate);
std::optional<RayShapeHit> rayVsSphere(const Vec3& origin, const Vec3& direction, Real max_t,
                                       const Vec3& center, Real radius);
// Grown boxes keep sharp edges (a slab test on half_extents + inflate): conservative for swept
// spheres, whose hits at edges and corners come at most (sqrt(3) - 1) inflate early.
std::optional<RayShapeHit> rayVsBox(const Vec3& origin, const Vec3& direction, Real max_t,
                                    const BoxCollider& box, Real inflate);
std::optional<RayShapeHit> rayVsCapsule(const Vec3& origin, const Vec3& direction, Real max_t,
                                        const CapsuleCollider& capsule, Real inflate);

// Earliest time s in [0, 1] at which two spheres moving linearly touch: |d0 + s dd| = sum of
// radii, with d0 the start offset of a from b and dd the relative displacement over the step.
// Nothing when they are already overlapping at the start or never touch.
std::optional<Real> sweptSpheresTimeOfImpact(const Vec3& d0, const Vec3& dd, Real radius_sum);

}  // namespace engine
}  // namespace mass_aggregate_sim
