// The box body shape kind (box_shape.h).
#include "mass_aggregate_sim/engine/bodies/box_shape.h"

#include "engine/collision/geometry.h"

namespace mass_aggregate_sim {
namespace engine {

Status BodyShapeKind<BoxShape>::validate(const BoxShape& box) {
  if (!(box.half_extents.allFinite() && (box.half_extents.array() > 0.0).all())) {
    return Status::error("box half_extents must be finite and > 0");
  }
  return Status::ok();
}

Real BodyShapeKind<BoxShape>::volume(const BoxShape& box) { return 8.0 * box.half_extents.prod(); }

// With full extents 2h: I_x = m (4 h_y^2 + 4 h_z^2) / 12 = m (h_y^2 + h_z^2) / 3, and so on.
Vec3 BodyShapeKind<BoxShape>::unitInertia(const BoxShape& box) {
  const Vec3 h2 = box.half_extents.cwiseProduct(box.half_extents);
  return volume(box) / 3.0 * Vec3(h2.y() + h2.z(), h2.z() + h2.x(), h2.x() + h2.y());
}

// The world half extents along axis i: sum over the box axes j of |R_ij| h_j.
Aabb BodyShapeKind<BoxShape>::aabb(const BoxShape& box, const Frame& frame) {
  const Vec3 extent = frame.rotation.cwiseAbs() * box.half_extents;
  return Aabb{frame.position - extent, frame.position + extent};
}

std::optional<RayShapeHit> BodyShapeKind<BoxShape>::raycast(const BoxShape& box, const Frame& frame,
                                                            const Vec3& origin,
                                                            const Vec3& direction,
                                                            const Real max_t) {
  const std::optional<RayShapeHit> hit = rayIntoCentredBox(
      frame.applyInverse(origin), frame.rotation.transpose() * direction, max_t, box.half_extents);
  if (!hit) return std::nullopt;
  return RayShapeHit{hit->t, frame.rotation * hit->normal};
}

std::vector<ShapePrimitive> BodyShapeKind<BoxShape>::describe(const BoxShape& box) {
  ShapePrimitive cube;
  cube.type = ShapePrimitive::Type::kBox;
  cube.size = 2.0 * box.half_extents;
  return {cube};
}

}  // namespace engine
}  // namespace mass_aggregate_sim
