#pragma once

#include "mass_aggregate_sim/engine/collision/shape_kind.h"

namespace mass_aggregate_sim {
namespace engine {

// All points within radius of the segment from a to b (a == b: a sphere).
struct CapsuleCollider {
  Vec3 a = Vec3::Zero();
  Vec3 b = Vec3::UnitZ();
  Real radius = 0.5;
  Material material;
  ColliderId id = 0;
};

template <>
struct ShapeKind<CapsuleCollider> {
  static constexpr const char* kName = "capsule";
  template <typename Visitor>
  static void fields(CapsuleCollider& capsule, Visitor& visit) {
    visit.point("a", capsule.a);
    visit.point("b", capsule.b);
    visit.length("radius", capsule.radius);
  }
  static Status validate(CapsuleCollider& capsule);
  static std::optional<ShapeContact> contact(const CapsuleCollider& capsule, const Vec3& x, Real r,
                                             Real margin);
  static std::optional<RayShapeHit> raycast(const CapsuleCollider& capsule, const Vec3& origin,
                                            const Vec3& direction, Real max_t, Real inflate);
  static ShapeDescription describe(const CapsuleCollider& capsule);
  static std::optional<Aabb> bounds(const CapsuleCollider& capsule);
  static void bodyContact(const CapsuleCollider& capsule, const AnyBodyShape& shape,
                          const Frame& frame, Real margin, Manifold& out);
};

}  // namespace engine
}  // namespace mass_aggregate_sim
