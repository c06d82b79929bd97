// The cylinder collider kind (cylinder.h).
#include "mass_aggregate_sim/engine/collision/cylinder.h"

#include <algorithm>
#include <cmath>

#include "engine/collision/geometry.h"
#include "engine/collision/narrowphase/any_shape.h"
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

std::optional<Aabb> ShapeKind<CylinderCollider>::bounds(const CylinderCollider& cylinder) {
  // Along each world axis k the cylinder reaches h |a_k| + R sqrt(1 - a_k^2) from its centre.
  const Vec3& a = cylinder.axis;
  Vec3 reach;
  for (int k = 0; k < 3; ++k) {
    reach[k] = cylinder.half_height * std::abs(a[k]) +
               cylinder.radius * std::sqrt(std::max(0.0, 1.0 - a[k] * a[k]));
  }
  return Aabb{cylinder.center - reach, cylinder.center + reach};
}

void ShapeKind<CylinderCollider>::bodyContact(const CylinderCollider& cylinder,
                                              const AnyBodyShape& shape, const Frame& frame,
                                              const Real margin, Manifold& out) {
  // Exact for a sphere. A box or a capsule meets the cylinder at its sample points, each a sphere
  // (a box's 8 corners, radius 0; a capsule's two end balls and its middle one): the deepest
  // sets the normal and at most four points along it are kept. A cylinder's rim poking into the
  // middle of a box face is missed (README, known limits).
  struct Sample {
    Vec3 center;
    Real radius;
  };
  Sample samples[8];
  int count = 0;
  if (const auto* sphere = std::get_if<SphereShape>(&shape)) {
    samples[count++] = Sample{frame.position, sphere->radius};
  } else if (const auto* box = std::get_if<BoxShape>(&shape)) {
    for (int corner = 0; corner < 8; ++corner) {
      const Vec3 sign((corner & 1) ? 1.0 : -1.0, (corner & 2) ? 1.0 : -1.0,
                      (corner & 4) ? 1.0 : -1.0);
      samples[count++] = Sample{frame.apply(box->half_extents.cwiseProduct(sign)), 0.0};
    }
  } else if (const auto* capsule = std::get_if<CapsuleShape>(&shape)) {
    for (const Real t : {-1.0, 0.0, 1.0}) {
      samples[count++] =
          Sample{frame.apply(Vec3(0.0, 0.0, t * capsule->half_length)), capsule->radius};
    }
  }
  out = Manifold{};
  std::optional<ShapeContact> found[8];
  int deepest = -1;
  for (int k = 0; k < count; ++k) {
    found[k] = contact(cylinder, samples[k].center, samples[k].radius, margin);
    if (found[k] && (deepest < 0 || found[k]->penetration > found[deepest]->penetration)) {
      deepest = k;
    }
  }
  if (deepest < 0) return;
  const Vec3 out_of_cylinder = found[deepest]->normal;
  out.normal = -out_of_cylinder;
  for (int k = 0; k < count && out.count < Manifold::kMaxPoints; ++k) {
    if (!found[k] || found[k]->normal.dot(out_of_cylinder) < 0.9) continue;
    ManifoldPoint& p = out.points[out.count++];
    p.separation = -found[k]->penetration;
    p.point =
        samples[k].center - out_of_cylinder * (samples[k].radius - 0.5 * found[k]->penetration);
    p.id = static_cast<std::uint32_t>(k);
  }
}

}  // namespace engine
}  // namespace mass_aggregate_sim
