// The capsule collider kind (capsule.h).
#include "mass_aggregate_sim/engine/collision/capsule.h"

#include "engine/collision/geometry.h"
#include "engine/collision/narrowphase/any_shape.h"
#include "engine/core/checks.h"

namespace mass_aggregate_sim {
namespace engine {

Status ShapeKind<CapsuleCollider>::validate(CapsuleCollider& capsule) {
  const Status material = checkMaterial(capsule.material);
  if (!material) return material;
  if (!(capsule.a.allFinite() && capsule.b.allFinite())) {
    return Status::error("capsule ends a and b must be finite");
  }
  if (!finitePositive(capsule.radius)) {
    return Status::error("capsule radius must be finite and > 0");
  }
  return Status::ok();
}

std::optional<ShapeContact> ShapeKind<CapsuleCollider>::contact(const CapsuleCollider& capsule,
                                                                const Vec3& x, const Real r,
                                                                const Real margin) {
  return sphereAgainstBall(x, r, closestOnSegment(x, capsule.a, capsule.b), capsule.radius, margin);
}

std::optional<RayShapeHit> ShapeKind<CapsuleCollider>::raycast(const CapsuleCollider& capsule,
                                                               const Vec3& origin,
                                                               const Vec3& direction,
                                                               const Real max_t,
                                                               const Real inflate) {
  return rayIntoCapsule(origin, direction, max_t, capsule.a, capsule.b, capsule.radius + inflate);
}

ShapeDescription ShapeKind<CapsuleCollider>::describe(const CapsuleCollider& capsule) {
  // Frame: z from a to b, origin at the middle. Drawn as a cylinder between two balls.
  ShapeDescription d;
  const Vec3 axis = capsule.b - capsule.a;
  d.origin = 0.5 * (capsule.a + capsule.b);
  d.orientation = Eigen::Quaterniond::FromTwoVectors(Vec3::UnitZ(), axis);
  const Real diameter = 2.0 * capsule.radius;
  ShapePrimitive cylinder;
  cylinder.type = ShapePrimitive::Type::kCylinder;
  cylinder.center = d.origin;
  cylinder.orientation = d.orientation;
  cylinder.size = Vec3(diameter, diameter, axis.norm());
  d.parts.push_back(cylinder);
  for (const Vec3& end : {capsule.a, capsule.b}) {
    ShapePrimitive ball;
    ball.type = ShapePrimitive::Type::kSphere;
    ball.center = end;
    ball.size = Vec3::Constant(diameter);
    d.parts.push_back(ball);
  }
  return d;
}

namespace {

// The capsule collider as a body capsule: its segment along the frame's z, centred.
Frame capsuleFrame(const CapsuleCollider& capsule) {
  const Vec3 axis = capsule.b - capsule.a;
  const Real length = axis.norm();
  const Mat3 rotation = length > 0.0
                            ? Quat::FromTwoVectors(Vec3::UnitZ(), axis / length).toRotationMatrix()
                            : Mat3::Identity();
  return Frame(0.5 * (capsule.a + capsule.b), rotation);
}

}  // namespace

std::optional<Aabb> ShapeKind<CapsuleCollider>::bounds(const CapsuleCollider& capsule) {
  const Vec3 r = Vec3::Constant(capsule.radius);
  return Aabb{capsule.a.cwiseMin(capsule.b) - r, capsule.a.cwiseMax(capsule.b) + r};
}

void ShapeKind<CapsuleCollider>::bodyContact(const CapsuleCollider& capsule,
                                             const AnyBodyShape& shape, const Frame& frame,
                                             const Real margin, Manifold& out) {
  const Real half_length = 0.5 * (capsule.b - capsule.a).norm();
  out = collideAnyWith(shape, frame, CapsuleShape{capsule.radius, half_length},
                       capsuleFrame(capsule), margin);
}

}  // namespace engine
}  // namespace mass_aggregate_sim
