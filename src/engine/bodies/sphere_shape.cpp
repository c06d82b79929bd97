// The sphere body shape kind (sphere_shape.h).
#include "mass_aggregate_sim/engine/bodies/sphere_shape.h"

#include <algorithm>
#include <cmath>

#include "engine/collision/geometry.h"
#include "engine/core/checks.h"

namespace mass_aggregate_sim {
namespace engine {

Status BodyShapeKind<SphereShape>::validate(const SphereShape& sphere) {
  if (!finitePositive(sphere.radius)) return Status::error("sphere radius must be finite and > 0");
  return Status::ok();
}

Real BodyShapeKind<SphereShape>::volume(const SphereShape& sphere) {
  return 4.0 / 3.0 * M_PI * std::pow(sphere.radius, 3);
}

// I = 2/5 m r^2 about any axis through the centre.
Vec3 BodyShapeKind<SphereShape>::unitInertia(const SphereShape& sphere) {
  return Vec3::Constant(0.4 * volume(sphere) * sphere.radius * sphere.radius);
}

Aabb BodyShapeKind<SphereShape>::aabb(const SphereShape& sphere, const Frame& frame) {
  const Vec3 r = Vec3::Constant(sphere.radius);
  return Aabb{frame.position - r, frame.position + r};
}

std::optional<RayShapeHit> BodyShapeKind<SphereShape>::raycast(const SphereShape& sphere,
                                                               const Frame& frame,
                                                               const Vec3& origin,
                                                               const Vec3& direction,
                                                               const Real max_t) {
  return rayIntoBall(origin, direction, max_t, frame.position, sphere.radius);
}

std::vector<ShapePrimitive> BodyShapeKind<SphereShape>::describe(const SphereShape& sphere) {
  ShapePrimitive ball;
  ball.type = ShapePrimitive::Type::kSphere;
  ball.size = Vec3::Constant(2.0 * sphere.radius);
  return {ball};
}

// The cap below the surface, of height d (d = r - s for the centre s above the surface):
//   V = pi d^2 (3r - d) / 3, its centroid 3 (2r - d)^2 / (4 (3r - d)) below the centre
// (3r/8 for the half ball, 0 for the whole).
SubmergedVolume BodyShapeKind<SphereShape>::submerged(const SphereShape& sphere, const Frame& frame,
                                                      const LiquidSurface& surface) {
  const Real r = sphere.radius;
  const Real d = std::min(r - surface.above(frame.position), 2.0 * r);
  if (d <= 0.0) return SubmergedVolume{};
  const Real volume = M_PI * d * d * (3.0 * r - d) / 3.0;
  const Real below = 3.0 * (2.0 * r - d) * (2.0 * r - d) / (4.0 * (3.0 * r - d));
  return SubmergedVolume{volume, volume * (frame.position - below * surface.up)};
}

}  // namespace engine
}  // namespace mass_aggregate_sim
