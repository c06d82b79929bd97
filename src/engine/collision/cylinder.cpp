// The cylinder collider kind (cylinder.h).
#include "mass_aggregate_sim/engine/collision/cylinder.h"

#include <algorithm>
#include <cmath>

#include "engine/collision/geometry.h"
#include "engine/core/checks.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

// Any unit vector at right angles to the unit vector a.
Vec3 perpendicular(const Vec3& a) {
  const Vec3 other = std::abs(a.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  return a.cross(other).normalized();
}

}  // namespace

Status ShapeKind<CylinderCollider>::validate(CylinderCollider& cylinder) {
  const Status material = checkMaterial(cylinder.material);
  if (!material) return material;
  if (!cylinder.center.allFinite()) return Status::error("cylinder center is not finite");
  if (!cylinder.axis.allFinite() || cylinder.axis.norm() < 1e-9) {
    return Status::error("cylinder axis must be a finite non-zero vector");
  }
  if (!finitePositive(cylinder.radius)) {
    return Status::error("cylinder radius must be finite and > 0");
  }
  if (!finitePositive(cylinder.half_height)) {
    return Status::error("cylinder half_height must be finite and > 0");
  }
  cylinder.axis.normalize();
  return Status::ok();
}

std::optional<ShapeContact> ShapeKind<CylinderCollider>::contact(const CylinderCollider& cylinder,
                                                                 const Vec3& x, const Real r,
                                                                 const Real margin) {
  // In the cylinder's frame: the height along the axis and the radial offset across it.
  const Vec3 offset = x - cylinder.center;
  const Real along = offset.dot(cylinder.axis);
  const Vec3 radial = offset - along * cylinder.axis;
  const Real distance_from_axis = radial.norm();
  const Real h = cylinder.half_height;
  const Real R = cylinder.radius;
  if (std::abs(along) > h || distance_from_axis > R) {
    // Outside: the nearest point of the solid (cap, side or rim) is the clamped one.
    const Real clamped_along = std::clamp(along, -h, h);
    const Vec3 clamped_radial =
        distance_from_axis > R ? Vec3(radial * (R / distance_from_axis)) : radial;
    const Vec3 d = offset - (clamped_along * cylinder.axis + clamped_radial);
    const Real distance = d.norm();
    const Real penetration = r - distance;
    if (!(penetration > -margin)) return std::nullopt;
    return ShapeContact{d / distance, penetration};
  }
  // Centre inside: leave through the nearer of the side and the cap.
  const Real to_cap = h - std::abs(along);
  const Real to_side = R - distance_from_axis;
  if (to_side < to_cap) {
    const Vec3 out = distance_from_axis > 1e-12 ? Vec3(radial / distance_from_axis)
                                                : perpendicular(cylinder.axis);
    return ShapeContact{out, r + to_side};
  }
  return ShapeContact{along >= 0.0 ? cylinder.axis : Vec3(-cylinder.axis), r + to_cap};
}

std::optional<RayShapeHit> ShapeKind<CylinderCollider>::raycast(const CylinderCollider& cylinder,
                                                                const Vec3& origin,
                                                                const Vec3& direction,
                                                                const Real max_t,
                                                                const Real inflate) {
  const Real h = cylinder.half_height + inflate;
  const Real R = cylinder.radius + inflate;
  const Vec3& axis = cylinder.axis;
  const Vec3 o = origin - cylinder.center;
  const Real o_along = o.dot(axis);
  const Real d_along = direction.dot(axis);
  const Vec3 o_radial = o - o_along * axis;
  const Vec3 d_radial = direction - d_along * axis;
  if (std::abs(o_along) < h && o_radial.squaredNorm() < R * R) return std::nullopt;  // inside
  std::optional<RayShapeHit> best;
  // The side: |o_r + t d_r| = R, entering (from outside the infinite cylinder) between the caps.
  const Real a = d_radial.squaredNorm();
  const Real b = o_radial.dot(d_radial);
  const Real c = o_radial.squaredNorm() - R * R;
  const Real discriminant = b * b - a * c;
  if (a > 0.0 && c > 0.0 && b < 0.0 && discriminant >= 0.0) {
    const Real t = (-b - std::sqrt(discriminant)) / a;
    const Real along = o_along + t * d_along;
    if (t >= 0.0 && t <= max_t && std::abs(along) <= h) {
      best = RayShapeHit{t, (o_radial + t * d_radial) / R};
    }
  }
  // The caps: the plane along = +-h, entered from outside it, within the radius.
  for (const Real side : {1.0, -1.0}) {
    const Real height = side * o_along - h;  // above the cap plane when > 0
    const Real approach = side * d_along;
    if (!(height > 0.0) || !(approach < 0.0)) continue;
    const Real t = -height / approach;
    if (t > max_t) continue;
    if ((o_radial + t * d_radial).squaredNorm() <= R * R) {
      best = earlier(best, RayShapeHit{t, side * axis});
    }
  }
  return best;
}

ShapeDescription ShapeKind<CylinderCollider>::describe(const CylinderCollider& cylinder) {
  // Frame: z along the axis, origin at the centre.
  ShapeDescription d;
  d.origin = cylinder.center;
  d.orientation = Eigen::Quaterniond::FromTwoVectors(Vec3::UnitZ(), cylinder.axis);
  ShapePrimitive body;
  body.type = ShapePrimitive::Type::kCylinder;
  body.center = cylinder.center;
  body.orientation = d.orientation;
  body.size = Vec3(2.0 * cylinder.radius, 2.0 * cylinder.radius, 2.0 * cylinder.half_height);
  d.parts.push_back(body);
  return d;
}

}  // namespace engine
}  // namespace mass_aggregate_sim
