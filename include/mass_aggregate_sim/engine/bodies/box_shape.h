#pragma once

#include "mass_aggregate_sim/engine/bodies/body_shape_kind.h"

namespace mass_aggregate_sim {
namespace engine {

// A box of the given half extents along its own axes, centred at its origin.
struct BoxShape {
  Vec3 half_extents = Vec3::Constant(0.5);
};

template <>
struct BodyShapeKind<BoxShape> {
  static constexpr const char* kName = "box";
  template <typename Visitor>
  static void fields(BoxShape& box, Visitor& visit) {
    visit.extents("half_extents", box.half_extents);
  }
  static Status validate(const BoxShape& box);
  static Real volume(const BoxShape& box);
  static Vec3 unitInertia(const BoxShape& box);
  static Aabb aabb(const BoxShape& box, const Frame& frame);
  static std::optional<RayShapeHit> raycast(const BoxShape& box, const Frame& frame,
                                            const Vec3& origin, const Vec3& direction, Real max_t);
  static std::vector<ShapePrimitive> describe(const BoxShape& box);
  static SubmergedVolume submerged(const BoxShape& box, const Frame& frame,
                                   const LiquidSurface& surface);
  static constexpr Real rounding(const BoxShape&) { return 0.0; }
};

}  // namespace engine
}  // namespace mass_aggregate_sim
