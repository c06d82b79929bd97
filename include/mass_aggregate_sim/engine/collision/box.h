#pragma once

#include "mass_aggregate_sim/engine/collision/shape_kind.h"

namespace mass_aggregate_sim {
namespace engine {

// An oriented box (normalised when added); the identity orientation takes a faster path.
struct BoxCollider {
  Vec3 center = Vec3::Zero();
  Vec3 half_extents = Vec3::Ones();
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
  Material material;
  ColliderId id = 0;
};

template <>
struct ShapeKind<BoxCollider> {
  static constexpr const char* kName = "box";
  template <typename Visitor>
  static void fields(BoxCollider& box, Visitor& visit) {
    visit.point("center", box.center);
    visit.extents("half_extents", box.half_extents);
    visit.orientation("orientation", box.orientation);
  }
  static Status validate(BoxCollider& box);
  static std::optional<ShapeContact> contact(const BoxCollider& box, const Vec3& x, Real r,
                                             Real margin);
  // Grown boxes keep sharp edges (a slab test on half_extents + inflate): conservative for swept
  // spheres, whose hits at edges and corners come at most (sqrt(3) - 1) inflate early.
  static std::optional<RayShapeHit> raycast(const BoxCollider& box, const Vec3& origin,
                                            const Vec3& direction, Real max_t, Real inflate);
  static ShapeDescription describe(const BoxCollider& box);
  static std::optional<Aabb> bounds(const BoxCollider& box);
  static void bodyContact(const BoxCollider& box, const AnyBodyShape& shape, const Frame& frame,
                          Real margin, Manifold& out);
};

}  // namespace engine
}  // namespace mass_aggregate_sim
