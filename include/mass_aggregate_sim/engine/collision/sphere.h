#pragma once

#include "mass_aggregate_sim/engine/collision/shape_kind.h"

namespace mass_aggregate_sim {
namespace engine {

struct SphereCollider {
  Vec3 center = Vec3::Zero();
  Real radius = 1.0;
  Material material;
  ColliderId id = 0;
};

template <>
struct ShapeKind<SphereCollider> {
  static constexpr const char* kName = "sphere";
  template <typename Visitor>
  static void fields(SphereCollider& sphere, Visitor& visit) {
    visit.point("center", sphere.center);
    visit.length("radius", sphere.radius);
  }
  static Status validate(SphereCollider& sphere);
  static std::optional<ShapeContact> contact(const SphereCollider& sphere, const Vec3& x, Real r,
                                             Real margin);
  static std::optional<RayShapeHit> raycast(const SphereCollider& sphere, const Vec3& origin,
                                            const Vec3& direction, Real max_t, Real inflate);
  static ShapeDescription describe(const SphereCollider& sphere);
  static std::optional<Aabb> bounds(const SphereCollider& sphere);
  static void bodyContact(const SphereCollider& sphere, const AnyBodyShape& shape,
                          const Frame& frame, Real margin, Manifold& out);
};

}  // namespace engine
}  // namespace mass_aggregate_sim
