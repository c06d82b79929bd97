#include "mass_aggregate_sim/engine/shape_geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mass_aggregate_sim {
namespace engine {
namespace {

constexpr Real kTinyLength = 1e-12;

bool axisAligned(const BoxCollider& box) {
  return box.orientation.w() == 1.0 && box.orientation.x() == 0.0 && box.orientation.y() == 0.0 &&
         box.orientation.z() == 0.0;
}

// Closest point to x on the segment a-b.
Vec3 closestOnSegment(const Vec3& x, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const Real length_squared = ab.squaredNorm();
  if (length_squared <= 0.0) return a;
  const Real t = std::clamp((x - a).dot(ab) / length_squared, Real{0.0}, Real{1.0});
  return a + t * ab;
}

std::optional<RayShapeHit> earlier(const std::optional<RayShapeHit>& x,
                                   const std::optional<RayShapeHit>& y) {
  if (!x) return y;
  if (!y) return x;
  return y->t < x->t ? y : x;
}

}  // namespace

std::optional<ShapeContact> sphereVsPlane(const Vec3& x, const Real r, const PlaneCollider& plane,
                                          const Real margin) {
  const Real distance = plane.normal.dot(x) - plane.offset;
  const Real penetration = r - distance;
  if (!(penetration > -margin)) return std::nullopt;
  return ShapeContact{plane.normal, penetration};
}

std::optional<ShapeContact> sphereVsSphere(const Vec3& x, const Real r, const Vec3& center,
                                           const Real radius, const Real margin) {
  const Vec3 d = x - center;
  const Real distance = d.norm();
  const Real penetration = r + radius - distance;
  if (!(penetration > -margin)) return std::nullopt;
  // Concentric: any direction separates them; pick up.
  const Vec3 normal = distance > kTinyLength ? Vec3(d / distance) : Vec3::UnitZ();
  return ShapeContact{normal, penetration};
}

std::optional<ShapeContact> sphereVsBox(const Vec3& x, const Real r, const BoxCollider& box,
                                        const Real margin) {
  const bool aligned = axisAligned(box);
  const Eigen::Matrix3d rotation =
      aligned ? Eigen::Matrix3d::Identity() : box.orientation.toRotationMatrix();
  const Vec3 local = aligned ? Vec3(x - box.center) : Vec3(rotation.transpose() * (x - box.center));
  const Vec3& h = box.half_extents;
  const Vec3 clamped = local.cwiseMax(-h).cwiseMin(h);
  const Vec3 outside = local - clamped;
  const Real outside_distance = outside.norm();
  if (outside_distance > 0.0) {
    // Centre outside the box: the nearest surface point is the clamped one (face, edge or corner).
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

std::optional<ShapeContact> sphereVsCapsule(const Vec3& x, const Real r,
                                            const CapsuleCollider& capsule, const Real margin) {
  return sphereVsSphere(x, r, closestOnSegment(x, capsule.a, capsule.b), capsule.radius, margin);
}

std::optional<RayShapeHit> rayVsPlane(const Vec3& origin, const Vec3& direction, const Real max_t,
                                      const PlaneCollider& plane, const Real inflate) {
  const Real height = plane.normal.dot(origin) - (plane.offset + inflate);
  if (!(height > 0.0)) return std::nullopt;
  const Real approach = plane.normal.dot(direction);
  if (!(approach < 0.0)) return std::nullopt;
  const Real t = -height / approach;
  if (t > max_t) return std::nullopt;
  return RayShapeHit{t, plane.normal};
}

std::optional<RayShapeHit> rayVsSphere(const Vec3& origin, const Vec3& direction, const Real max_t,
                                       const Vec3& center, const Real radius) {
  // |o + t d - c|^2 = R^2 with |d| = 1:  t^2 + 2 b t + c = 0,  b = (o - c).d,  c = |o - c|^2 - R^2
  const Vec3 offset = origin - center;
  const Real c = offset.squaredNorm() - radius * radius;
  if (!(c > 0.0)) return std::nullopt;
  const Real b = offset.dot(direction);
  if (b >= 0.0) return std::nullopt;
  const Real discriminant = b * b - c;
  if (discriminant < 0.0) return std::nullopt;
  const Real t = -b - std::sqrt(discriminant);
  if (t < 0.0 || t > max_t) return std::nullopt;
  const Vec3 normal = (offset + t * direction) / radius;
  return RayShapeHit{t, radius > 0.0 ? normal : Vec3(-direction)};
}

std::optional<RayShapeHit> rayVsBox(const Vec3& origin, const Vec3& direction, const Real max_t,
                                    const BoxCollider& box, const Real inflate) {
  const bool aligned = axisAligned(box);
  const Eigen::Matrix3d rotation =
      aligned ? Eigen::Matrix3d::Identity() : box.orientation.toRotationMatrix();
  const Vec3 o =
      aligned ? Vec3(origin - box.center) : Vec3(rotation.transpose() * (origin - box.center));
  const Vec3 d = aligned ? direction : Vec3(rotation.transpose() * direction);
  const Vec3 h = box.half_extents + Vec3::Constant(inflate);
  if ((o.cwiseAbs().array() < h.array()).all()) return std::nullopt;  // starts inside
  // Slabs: the ray is inside the box between the last entry and the first exit.
  Real enter = -std::numeric_limits<Real>::infinity();
  Real exit = std::numeric_limits<Real>::infinity();
  int enter_axis = -1;
  Real enter_sign = 0.0;
  for (int k = 0; k < 3; ++k) {
    if (d[k] == 0.0) {
      if (std::abs(o[k]) > h[k]) return std::nullopt;
      continue;
    }
    const Real near_face = d[k] > 0.0 ? -h[k] : h[k];
    const Real t_near = (near_face - o[k]) / d[k];
    const Real t_far = (-near_face - o[k]) / d[k];
    if (t_near > enter) {
      enter = t_near;
      enter_axis = k;
      enter_sign = d[k] > 0.0 ? -1.0 : 1.0;
    }
    exit = std::min(exit, t_far);
  }
  if (enter_axis < 0 || enter > exit || enter < 0.0 || enter > max_t) return std::nullopt;
  Vec3 normal = Vec3::Zero();
  normal[enter_axis] = enter_sign;
  return RayShapeHit{enter, rotation * normal};
}

std::optional<RayShapeHit> rayVsCapsule(const Vec3& origin, const Vec3& direction, const Real max_t,
                                        const CapsuleCollider& capsule, const Real inflate) {
  const Real radius = capsule.radius + inflate;
  if ((origin - closestOnSegment(origin, capsule.a, capsule.b)).squaredNorm() <= radius * radius) {
    return std::nullopt;  // starts inside
  }
  // The capsule is the union of its cylinder and two end spheres; starting outside all of them,
  // the first entry into the union is the earliest entry into any part.
  std::optional<RayShapeHit> best =
      earlier(rayVsSphere(origin, direction, max_t, capsule.a, radius),
              rayVsSphere(origin, direction, max_t, capsule.b, radius));
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

std::optional<Real> sweptSpheresTimeOfImpact(const Vec3& d0, const Vec3& dd,
                                             const Real radius_sum) {
  // |d0 + s dd|^2 = R^2:  a s^2 + 2 b s + c = 0
  const Real c = d0.squaredNorm() - radius_sum * radius_sum;
  if (!(c > 0.0)) return std::nullopt;
  const Real b = d0.dot(dd);
  if (!(b < 0.0)) return std::nullopt;
  const Real a = dd.squaredNorm();
  const Real discriminant = b * b - a * c;
  if (discriminant < 0.0) return std::nullopt;
  const Real s = (-b - std::sqrt(discriminant)) / a;
  if (s < 0.0 || s > 1.0) return std::nullopt;
  return s;
}

}  // namespace engine
}  // namespace mass_aggregate_sim
