#pragma once

#include "mass_aggregate_sim/engine/bodies/body_shape_kind.h"

namespace mass_aggregate_sim {
namespace engine {

// All points within radius of the segment from (0, 0, -half_length) to (0, 0, half_length) of its
// own frame: a cylinder along z with a hemisphere on each end.
struct CapsuleShape {
  Real radius = 0.25;
  Real half_length = 0.5;
};

template <>
struct BodyShapeKind<CapsuleShape> {
  static constexpr const char* kName = "capsule";
  template <typename Visitor>
  static void fields(CapsuleShape& capsule, Visitor& visit) {
    visit.length("radius", capsule.radius);
    visit.length("half_length", capsule.half_length);
  }
  static Status validate(const CapsuleShape& capsule);
  static Real volume(const CapsuleShape& capsule);
  static Vec3 unitInertia(const CapsuleShape& capsule);
  static Aabb aabb(const CapsuleShape& capsule, const Frame& frame);
  static std::optional<RayShapeHit> raycast(const CapsuleShape& capsule, const Frame& frame,
                                            const Vec3& origin, const Vec3& direction, Real max_t);
  static std::vector<ShapePrimitive> describe(const CapsuleShape& capsule);
  static SubmergedVolume submerged(const CapsuleShape& capsule, const Frame& frame,
                                   const LiquidSurface& surface);
  static constexpr Real rounding(const CapsuleShape& capsule) { return capsule.radius; }
};

}  // namespace engine
}  // namespace mass_aggregate_sim
