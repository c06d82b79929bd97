// The oriented box collider kind (box.h).
#include "mass_aggregate_sim/engine/collision/box.h"

#include "engine/collision/geometry.h"
#include "engine/collision/narrowphase/any_shape.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

bool axisAligned(const BoxCollider& box) {
  return box.orientation.w() == 1.0 && box.orientation.x() == 0.0 && box.orientation.y() == 0.0 &&
         box.orientation.z() == 0.0;
}

}  // namespace

Status ShapeKind<BoxCollider>::validate(BoxCollider& box) {
  const Status material = checkMaterial(box.material);
  if (!material) return material;
  if (!box.center.allFinite()) return Status::error("box center is not finite");
  if (!(box.half_extents.allFinite() && (box.half_extents.array() > 0.0).all())) {
    return Status::error("box half_extents must be finite and > 0");
  }
  if (!box.orientation.coeffs().allFinite() || box.orientation.norm() < 1e-9) {
    return Status::error("box orientation must be a finite non-zero quaternion");
  }
  box.orientation.normalize();
  return Status::ok();
}

std::optional<ShapeContact> ShapeKind<BoxCollider>::contact(const BoxCollider& box, const Vec3& x,
                                                            const Real r, const Real margin) {
  const bool aligned = axisAligned(box);
  const Eigen::Matrix3d rotation =
      aligned ? Eigen::Matrix3d::Identity() : box.orientation.toRotationMatrix();
  const Vec3 local = aligned ? Vec3(x - box.center) : Vec3(rotation.transpose() * (x - box.center));
  const Vec3& h = box.half_extents;
  const Vec3 clamped = local.cwiseMax(-h).cwiseMin(h);
  const Vec3 outside = local - clamped;
  const Real outside_squared = outside.squaredNorm();
  if (outside_squared > 0.0) {
    // Centre outside the box: the nearest surface point is the clamped one (face, edge or corner).
    if (certainlyBeyond(outside_squared, r + margin)) return std::nullopt;
    const Real outside_distance = std::sqrt(outside_squared);
    const Real penetration = r - outside_distance;
    if (!(penetration > -margin)) return std::nullopt;
    return ShapeContact{rotation * (outside / outside_distance), penetration};
  }
  // Centre inside: leave through the nearest face.
  const Vec3 to_face = h - local.cwiseAbs();
  Eigen::Index axis = 0;
  to_face.minCoeff(&axis);
  Vec3 normal = Vec3::Zero();
  normal[axis] = local[axis] >= 0.0 ? 1.0 : -1.0;
  return ShapeContact{rotation * normal, r + to_face[axis]};
}

std::optional<RayShapeHit> ShapeKind<BoxCollider>::raycast(const BoxCollider& box,
                                                           const Vec3& origin,
                                                           const Vec3& direction, const Real max_t,
                                                           const Real inflate) {
  const bool aligned = axisAligned(box);
  const Eigen::Matrix3d rotation =
      aligned ? Eigen::Matrix3d::Identity() : box.orientation.toRotationMatrix();
  const Vec3 o =
      aligned ? Vec3(origin - box.center) : Vec3(rotation.transpose() * (origin - box.center));
  const Vec3 d = aligned ? direction : Vec3(rotation.transpose() * direction);
  const std::optional<RayShapeHit> hit =
      rayIntoCentredBox(o, d, max_t, box.half_extents + Vec3::Constant(inflate));
  if (!hit) return std::nullopt;
  return RayShapeHit{hit->t, rotation * hit->normal};
}

ShapeDescription ShapeKind<BoxCollider>::describe(const BoxCollider& box) {
  ShapeDescription d;
  d.origin = box.center;
  d.orientation = box.orientation.normalized();
  ShapePrimitive cube;
  cube.type = ShapePrimitive::Type::kBox;
  cube.center = box.center;
  cube.orientation = d.orientation;
  cube.size = 2.0 * box.half_extents;
  d.parts.push_back(cube);
  return d;
}

std::optional<Aabb> ShapeKind<BoxCollider>::bounds(const BoxCollider& box) {
  const BoxShape shape{box.half_extents};
  return BodyShapeKind<BoxShape>::aabb(shape,
                                       Frame(box.center, box.orientation.toRotationMatrix()));
}

void ShapeKind<BoxCollider>::bodyContact(const BoxCollider& box, const AnyBodyShape& shape,
                                         const Frame& frame, const Real margin, Manifold& out) {
  out = collideAnyWith(shape, frame, BoxShape{box.half_extents},
                       Frame(box.center, box.orientation.toRotationMatrix()), margin);
}

}  // namespace engine
}  // namespace mass_aggregate_sim
