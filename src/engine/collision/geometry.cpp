#include "engine/collision/geometry.h"

namespace mass_aggregate_sim {
namespace engine {

std::optional<ShapeContact> sphereAgainstBall(const Vec3& x, const Real r, const Vec3& center,
                                              const Real radius, const Real margin) {
  constexpr Real kTinyLength = 1e-12;
  const Vec3 d = x - center;
  const Real distance = d.norm();
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
  if (t < 0.0 || t > max_t) return std::nullopt;
  const Vec3 normal = (offset + t * direction) / radius;
  return RayShapeHit{t, radius > 0.0 ? normal : Vec3(-direction)};
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
