#pragma once
// The narrowphase for shapes whose kind is known only at run time (AnyBodyShape): a visit over the
// kinds, then the pair table.

#include <variant>

#include "engine/collision/narrowphase/pair_table.h"
#include "mass_aggregate_sim/engine/bodies/body_shapes.h"

namespace mass_aggregate_sim {
namespace engine {

inline Manifold collideAny(const AnyBodyShape& a, const Frame& fa, const AnyBodyShape& b,
                           const Frame& fb, const Real margin) {
  return std::visit(
      [&](const auto& x, const auto& y) { return collideShapes(x, fa, y, fb, margin); }, a, b);
}

template <typename B>
Manifold collideAnyWith(const AnyBodyShape& a, const Frame& fa, const B& b, const Frame& fb,
                        const Real margin) {
  return std::visit([&](const auto& x) { return collideShapes(x, fa, b, fb, margin); }, a);
}

inline Manifold collideAnyWithPlane(const AnyBodyShape& a, const Frame& fa, const Vec3& normal,
                                    const Real offset, const Real margin) {
  return std::visit([&](const auto& x) { return collideWithPlane(x, fa, normal, offset, margin); },
                    a);
}

inline Real shapeRounding(const AnyBodyShape& shape) {
  return std::visit(
      [](const auto& x) { return BodyShapeKind<std::decay_t<decltype(x)>>::rounding(x); }, shape);
}

inline Aabb shapeBounds(const AnyBodyShape& shape, const Frame& frame) {
  return std::visit(
      [&](const auto& x) { return BodyShapeKind<std::decay_t<decltype(x)>>::aabb(x, frame); },
      shape);
}

}  // namespace engine
}  // namespace mass_aggregate_sim
