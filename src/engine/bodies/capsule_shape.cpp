// The capsule body shape kind (capsule_shape.h).
#include "mass_aggregate_sim/engine/bodies/capsule_shape.h"

#include <cmath>

#include "engine/collision/geometry.h"
#include "engine/core/checks.h"

namespace mass_aggregate_sim {
namespace engine {

Status BodyShapeKind<CapsuleShape>::validate(const CapsuleShape& capsule) {
  if (!finitePositive(capsule.radius)) {
    return Status::error("capsule radius must be finite and > 0");
  }
  if (!finitePositive(capsule.half_length)) {
    return Status::error("capsule half_length must be finite and > 0");
  }
  return Status::ok();
}

Real BodyShapeKind<CapsuleShape>::volume(const CapsuleShape& capsule) {
  const Real r = capsule.radius;
  return M_PI * r * r * (2.0 * capsule.half_length + 4.0 / 3.0 * r);
}

// Cylinder (mass m_c, height 2h): I_z = m_c r^2 / 2, I_x = m_c (3 r^2 + 4 h^2) / 12.
// Each hemisphere (mass m_h = 2/3 pi r^3): I_z = 2/5 m_h r^2; about a transverse axis through its
// flat face also 2/5 m_h r^2. Its centroid lies 3r/8 from that face, so moving the axis to the
// centroid and then to the capsule's centre (h + 3r/8 away) gives
// 2/5 m_h r^2 - m_h (3r/8)^2 + m_h (h + 3r/8)^2 = m_h (2/5 r^2 + h^2 + 3/4 h r).
Vec3 BodyShapeKind<CapsuleShape>::unitInertia(const CapsuleShape& capsule) {
  const Real r = capsule.radius;
  const Real h = capsule.half_length;
  const Real cylinder = M_PI * r * r * 2.0 * h;
  const Real hemisphere = 2.0 / 3.0 * M_PI * r * r * r;
  const Real axial = 0.5 * cylinder * r * r + 2.0 * 0.4 * hemisphere * r * r;
  const Real transverse = cylinder * (3.0 * r * r + 4.0 * h * h) / 12.0 +
                          2.0 * hemisphere * (0.4 * r * r + h * h + 0.75 * h * r);
  return Vec3(transverse, transverse, axial);
}

Aabb BodyShapeKind<CapsuleShape>::aabb(const CapsuleShape& capsule, const Frame& frame) {
  const Vec3 extent =
      frame.rotation.col(2).cwiseAbs() * capsule.half_length + Vec3::Constant(capsule.radius);
  return Aabb{frame.position - extent, frame.position + extent};
}

std::optional<RayShapeHit> BodyShapeKind<CapsuleShape>::raycast(const CapsuleShape& capsule,
                                                                const Frame& frame,
                                                                const Vec3& origin,
                                                                const Vec3& direction,
                                                                const Real max_t) {
  const Vec3 half_axis = frame.rotation.col(2) * capsule.half_length;
  return rayIntoCapsule(origin, direction, max_t, frame.position - half_axis,
                        frame.position + half_axis, capsule.radius);
}

std::vector<ShapePrimitive> BodyShapeKind<CapsuleShape>::describe(const CapsuleShape& capsule) {
  const Real diameter = 2.0 * capsule.radius;
  std::vector<ShapePrimitive> parts(3);
  parts[0].type = ShapePrimitive::Type::kCylinder;
  parts[0].size = Vec3(diameter, diameter, 2.0 * capsule.half_length);
  for (int end = 0; end < 2; ++end) {
    ShapePrimitive& ball = parts[1 + end];
    ball.type = ShapePrimitive::Type::kSphere;
    ball.center = Vec3(0.0, 0.0, end == 0 ? -capsule.half_length : capsule.half_length);
    ball.size = Vec3::Constant(diameter);
  }
  return parts;
}

}  // namespace engine
}  // namespace mass_aggregate_sim
