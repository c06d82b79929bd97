#pragma once

#include "mass_aggregate_sim/engine/bodies/body_shape_kind.h"

namespace mass_aggregate_sim {
namespace engine {

// A ball of the given radius about its origin.
struct SphereShape {
  Real radius = 0.5;
};

template <>
struct BodyShapeKind<SphereShape> {
  static constexpr const char* kName = "sphere";
  template <typename Visitor>
  static void fields(SphereShape& sphere, Visitor& visit) {
    visit.length("radius", sphere.radius);
  }
  static Status validate(const SphereShape& sphere);
  static Real volume(const SphereShape& sphere);
  static Vec3 unitInertia(const SphereShape& sphere);
  static Aabb aabb(const SphereShape& sphere, const Frame& frame);
  static std::optional<RayShapeHit> raycast(const SphereShape& sphere, const Frame& frame,
                                            const Vec3& origin, const Vec3& direction, Real max_t);
  static std::vector<ShapePrimitive> describe(const SphereShape& sphere);
  static SubmergedVolume submerged(const SphereShape& sphere, const Frame& frame,
                                   const LiquidSurface& surface);
  static constexpr Real rounding(const SphereShape& sphere) { return sphere.radius; }
};

}  // namespace engine
}  // namespace mass_aggregate_sim
