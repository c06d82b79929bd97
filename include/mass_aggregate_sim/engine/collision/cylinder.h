#pragma once

#include "mass_aggregate_sim/engine/collision/shape_kind.h"

namespace mass_aggregate_sim {
namespace engine {

// A solid circular cylinder: the points within radius of its axis and within half_height of its
// centre along the axis (normalised when added), flat caps and a sharp rim.
struct CylinderCollider {
  Vec3 center = Vec3::Zero();
  Vec3 axis = Vec3::UnitZ();
  Real radius = 0.5;
  Real half_height = 0.5;
  Material material;
  ColliderId id = 0;
};

template <>
struct ShapeKind<CylinderCollider> {
  static constexpr const char* kName = "cylinder";
  template <typename Visitor>
  static void fields(CylinderCollider& cylinder, Visitor& visit) {
    visit.point("center", cylinder.center);
    visit.direction("axis", cylinder.axis);
    visit.length("radius", cylinder.radius);
    visit.length("half_height", cylinder.half_height);
  }
  static Status validate(CylinderCollider& cylinder);
  static std::optional<ShapeContact> contact(const CylinderCollider& cylinder, const Vec3& x,
                                             Real r, Real margin);
  // Grown cylinders keep their sharp rim (radius + inflate, half_height + inflate): conservative
  // for swept spheres, like the box's edges.
  static std::optional<RayShapeHit> raycast(const CylinderCollider& cylinder, const Vec3& origin,
                                            const Vec3& direction, Real max_t, Real inflate);
  static ShapeDescription describe(const CylinderCollider& cylinder);
  static std::optional<Aabb> bounds(const CylinderCollider& cylinder);
  static void bodyContact(const CylinderCollider& cylinder, const AnyBodyShape& shape,
                          const Frame& frame, Real margin, Manifold& out);
};

}  // namespace engine
}  // namespace mass_aggregate_sim
