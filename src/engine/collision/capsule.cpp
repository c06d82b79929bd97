// The capsule collider kind (capsule.h).
#include "mass_aggregate_sim/engine/collision/capsule.h"

#include "engine/collision/geometry.h"
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
  const Real radius = capsule.radius + inflate;
  if ((origin - closestOnSegment(origin, capsule.a, capsule.b)).squaredNorm() <= radius * radius) {
    return std::nullopt;  // starts inside
  }
  // The capsule is the union of its cylinder and two end balls; starting outside all of them,
  // the first entry into the union is the earliest entry into any part.
  std::optional<RayShapeHit> best =
      earlier(rayIntoBall(origin, direction, max_t, capsule.a, radius),
              rayIntoBall(origin, direction, max_t, capsule.b, radius));
  const Vec3 axis = capsule.b - capsule.a;
  const Real axis_squared = axis.squaredNorm();
  if (axis_squared > 0.0) {
    // Remove the axial parts: |w + t e| = R with w, e the components of (o - a) and d across the
    // axis, then keep hits whose axial coordinate lies between the ends.
    const Vec3 oa = origin - capsule.a;
    const Vec3 w = oa - axis * (oa.dot(axis) / axis_squared);
    const Vec3 e = direction - axis * (direction.dot(axis) / axis_squared);
    const Real a = e.squaredNorm();
    const Real b = w.dot(e);
    const Real c = w.squaredNorm() - radius * radius;
    const Real discriminant = b * b - a * c;
    if (a > 0.0 && c > 0.0 && b < 0.0 && discriminant >= 0.0) {
      const Real t = (-b - std::sqrt(discriminant)) / a;
      const Real along = (oa + t * direction).dot(axis) / axis_squared;
      if (t >= 0.0 && t <= max_t && along >= 0.0 && along <= 1.0) {
        const Vec3 normal = (w + t * e) / radius;
        best = earlier(best, RayShapeHit{t, normal});
      }
    }
  }
  return best;
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

}  // namespace engine
}  // namespace mass_aggregate_sim
