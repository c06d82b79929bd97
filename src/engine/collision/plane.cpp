// The plane (half-space) collider kind (plane.h).
#include "mass_aggregate_sim/engine/collision/plane.h"

#include <cmath>

#include "engine/collision/geometry.h"
#include "engine/collision/narrowphase/any_shape.h"

namespace mass_aggregate_sim {
namespace engine {

Status ShapeKind<PlaneCollider>::validate(PlaneCollider& plane) {
  const Status material = checkMaterial(plane.material);
  if (!material) return material;
  if (!plane.normal.allFinite() || plane.normal.norm() < 1e-9) {
    return Status::error("plane normal must be a finite non-zero vector");
  }
  if (!std::isfinite(plane.offset)) return Status::error("plane offset is not finite");
  // n.x < offset stays the same half-space after dividing both sides by |n|.
  const Real length = plane.normal.norm();
  plane.normal /= length;
  plane.offset /= length;
  return Status::ok();
}

std::optional<RayShapeHit> ShapeKind<PlaneCollider>::raycast(const PlaneCollider& plane,
                                                             const Vec3& origin,
                                                             const Vec3& direction,
                                                             const Real max_t, const Real inflate) {
  const Real height = plane.normal.dot(origin) - (plane.offset + inflate);
  if (!(height > 0.0)) return std::nullopt;
  const Real approach = plane.normal.dot(direction);
  if (!(approach < 0.0)) return std::nullopt;
  const Real t = -height / approach;
  if (t > max_t) return std::nullopt;
  return RayShapeHit{t, plane.normal};
}

ShapeDescription ShapeKind<PlaneCollider>::describe(const PlaneCollider& plane) {
  // Frame: z along the normal, at the plane's point nearest the origin (normal.x = offset). Drawn
  // as a 40 m square slab whose top face is the plane.
  ShapeDescription d;
  d.origin = plane.normal * plane.offset;
  d.orientation = Eigen::Quaterniond::FromTwoVectors(Vec3::UnitZ(), plane.normal);
  d.surface = true;
  ShapePrimitive slab;
  slab.type = ShapePrimitive::Type::kBox;
  slab.center = plane.normal * (plane.offset - 0.005);
  slab.orientation = d.orientation;
  slab.size = Vec3(40.0, 40.0, 0.01);
  d.parts.push_back(slab);
  return d;
}

std::optional<Aabb> ShapeKind<PlaneCollider>::bounds(const PlaneCollider&) { return std::nullopt; }

void ShapeKind<PlaneCollider>::bodyContact(const PlaneCollider& plane, const AnyBodyShape& shape,
                                           const Frame& frame, const Real margin, Manifold& out) {
  out = collideAnyWithPlane(shape, frame, plane.normal, plane.offset, margin);
}

}  // namespace engine
}  // namespace mass_aggregate_sim
