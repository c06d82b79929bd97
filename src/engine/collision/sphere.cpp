// The sphere collider kind (sphere.h).
#include "mass_aggregate_sim/engine/collision/sphere.h"

#include "engine/collision/geometry.h"
#include "engine/collision/narrowphase/any_shape.h"
#include "engine/core/checks.h"

namespace mass_aggregate_sim {
namespace engine {

Status ShapeKind<SphereCollider>::validate(SphereCollider& sphere) {
  const Status material = checkMaterial(sphere.material);
  if (!material) return material;
  if (!sphere.center.allFinite()) return Status::error("sphere center is not finite");
  if (!finitePositive(sphere.radius)) return Status::error("sphere radius must be finite and > 0");
  return Status::ok();
}

std::optional<ShapeContact> ShapeKind<SphereCollider>::contact(const SphereCollider& sphere,
                                                               const Vec3& x, const Real r,
                                                               const Real margin) {
  return sphereAgainstBall(x, r, sphere.center, sphere.radius, margin);
}

std::optional<RayShapeHit> ShapeKind<SphereCollider>::raycast(const SphereCollider& sphere,
                                                              const Vec3& origin,
                                                              const Vec3& direction,
                                                              const Real max_t,
                                                              const Real inflate) {
  return rayIntoBall(origin, direction, max_t, sphere.center, sphere.radius + inflate);
}

ShapeDescription ShapeKind<SphereCollider>::describe(const SphereCollider& sphere) {
  ShapeDescription d;
  d.origin = sphere.center;
  ShapePrimitive ball;
  ball.type = ShapePrimitive::Type::kSphere;
  ball.center = sphere.center;
  ball.size = Vec3::Constant(2.0 * sphere.radius);
  d.parts.push_back(ball);
  return d;
}

std::optional<Aabb> ShapeKind<SphereCollider>::bounds(const SphereCollider& sphere) {
  const Vec3 r = Vec3::Constant(sphere.radius);
  return Aabb{sphere.center - r, sphere.center + r};
}

void ShapeKind<SphereCollider>::bodyContact(const SphereCollider& sphere, const AnyBodyShape& shape,
                                            const Frame& frame, const Real margin, Manifold& out) {
  out = collideAnyWith(shape, frame, SphereShape{sphere.radius},
                       Frame(sphere.center, Mat3::Identity()), margin);
}

}  // namespace engine
}  // namespace mass_aggregate_sim
