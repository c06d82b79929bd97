#pragma once

#include "mass_aggregate_sim/engine/collision/shape_kind.h"

namespace mass_aggregate_sim {
namespace engine {

// A half-space: solid where normal.x < offset. The ground is {normal = up, offset = 0}. The normal
// is normalised when added (offset scaled with it: the same half-space).
struct PlaneCollider {
  Vec3 normal = Vec3::UnitZ();
  Real offset = 0.0;
  Material material;
  ColliderId id = 0;
};

template <>
struct ShapeKind<PlaneCollider> {
  static constexpr const char* kName = "plane";
  template <typename Visitor>
  static void fields(PlaneCollider& plane, Visitor& visit) {
    visit.direction("normal", plane.normal);
    visit.coordinate("offset", plane.offset);
  }
  static Status validate(PlaneCollider& plane);
  // How deep a sphere at (x, y, z) with radius r reaches into the half-space, r - (n.x - offset),
  // for T a scalar or a vector of lanes (the solver tests four particles at once).
  template <typename T>
  static T depth(const PlaneCollider& plane, const T x, const T y, const T z, const T r) {
    const T distance = (x * plane.normal.x() + y * plane.normal.y()) + z * plane.normal.z();
    return r - (distance - plane.offset);
  }
  // Inline: every particle meets every plane, and most are far from it.
  static std::optional<ShapeContact> contact(const PlaneCollider& plane, const Vec3& x, Real r,
                                             Real margin) {
    const Real penetration = depth(plane, x.x(), x.y(), x.z(), r);
    if (!(penetration > -margin)) return std::nullopt;
    return ShapeContact{plane.normal, penetration};
  }
  static std::optional<RayShapeHit> raycast(const PlaneCollider& plane, const Vec3& origin,
                                            const Vec3& direction, Real max_t, Real inflate);
  static ShapeDescription describe(const PlaneCollider& plane);
  static std::optional<Aabb> bounds(const PlaneCollider& plane);
  static void bodyContact(const PlaneCollider& plane, const AnyBodyShape& shape, const Frame& frame,
                          Real margin, Manifold& out);
};

}  // namespace engine
}  // namespace mass_aggregate_sim
