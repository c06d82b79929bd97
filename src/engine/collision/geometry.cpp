#include "engine/collision/geometry.h"

#include <limits>

namespace mass_aggregate_sim {
namespace engine {

std::optional<ShapeContact> sphereAgainstBall(const Vec3& x, const Real r, const Vec3& center,
                                              const Real radius, const Real margin) {
  constexpr Real kTinyLength = 1e-12;
  const Vec3 d = x - center;
  const Real squared_distance = d.squaredNorm();
  if (certainlyBeyond(squared_distance, r + radius + margin)) return std::nullopt;
  const Real distance = std::sqrt(squared_distance);
  const Real penetration = r + radius - distance;
  if (!(penetration > -margin)) return std::nullopt;
  // Concentric: any direction separates them; pick up.
  const Vec3 normal = distance > kTinyLength ? Vec3(d / distance) : Vec3::UnitZ();
  return ShapeContact{normal, penetration};
}

std::optional<RayShapeHit> rayIntoBall(const Vec3& origin, const Vec3& direction, const Real max_t,
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
  if (!(t >= 0.0 && t <= max_t)) return std::nullopt;
  const Vec3 normal = (offset + t * direction) / radius;
  return RayShapeHit{t, radius > 0.0 ? normal : Vec3(-direction)};
}

std::optional<RayShapeHit> rayIntoCentredBox(const Vec3& o, const Vec3& d, const Real max_t,
                                             const Vec3& h) {
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
  return RayShapeHit{enter, normal};
}

std::optional<RayShapeHit> rayIntoCapsule(const Vec3& origin, const Vec3& direction,
                                          const Real max_t, const Vec3& a, const Vec3& b,
                                          const Real radius) {
  if ((origin - closestOnSegment(origin, a, b)).squaredNorm() <= radius * radius) {
    return std::nullopt;  // starts inside
  }
  // The capsule is the union of its cylinder and two end balls; starting outside all of them,
  // the first entry into the union is the earliest entry into any part.
  std::optional<RayShapeHit> best = earlier(rayIntoBall(origin, direction, max_t, a, radius),
                                            rayIntoBall(origin, direction, max_t, b, radius));
  const Vec3 axis = b - a;
  const Real axis_squared = axis.squaredNorm();
  if (axis_squared > 0.0) {
    // Remove the axial parts: |w + t e| = R with w, e the components of (o - a) and d across the
    // axis, then keep hits whose axial coordinate lies between the ends.
    const Vec3 oa = origin - a;
    const Vec3 w = oa - axis * (oa.dot(axis) / axis_squared);
    const Vec3 e = direction - axis * (direction.dot(axis) / axis_squared);
    const Real qa = e.squaredNorm();
    const Real qb = w.dot(e);
    const Real qc = w.squaredNorm() - radius * radius;
    const Real discriminant = qb * qb - qa * qc;
    if (qa > 0.0 && qc > 0.0 && qb < 0.0 && discriminant >= 0.0) {
      const Real t = (-qb - std::sqrt(discriminant)) / qa;
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

Status checkMaterial(const Material& material) {
  if (!std::isfinite(material.restitution) || material.restitution < 0.0 ||
      material.restitution > 1.0) {
    return Status::error("restitution must be in [0, 1]");
  }
  if (!std::isfinite(material.friction) || material.friction < 0.0) {
    return Status::error("friction must be finite and >= 0");
  }
  return Status::ok();
}

}  // namespace engine
}  // namespace mass_aggregate_sim
