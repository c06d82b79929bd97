#pragma once
// The narrowphase's dispatch: collideShapes<A, B> for every ordered pair of BodyShapeKinds calls
// the pair function written for (A, B), or the one for (B, A) with the normal flipped (points,
// separations and ids are the same either way). collideWithPlaneShape<A> likewise for the
// half-space. The static_asserts below stop the build when a kind lacks a pair function.

#include <type_traits>
#include <utility>

#include "engine/collision/narrowphase/narrowphase.h"

namespace mass_aggregate_sim {
namespace engine {
namespace narrowphase_detail {

template <typename A, typename B, typename = void>
struct HasPairFunction : std::false_type {};
template <typename A, typename B>
struct HasPairFunction<
    A, B,
    std::void_t<decltype(collide(std::declval<const A&>(), std::declval<const Frame&>(),
                                 std::declval<const B&>(), std::declval<const Frame&>(), Real{}))>>
    : std::true_type {};

template <typename A, typename = void>
struct HasPlaneFunction : std::false_type {};
template <typename A>
struct HasPlaneFunction<
    A, std::void_t<decltype(collideWithPlane(std::declval<const A&>(), std::declval<const Frame&>(),
                                             std::declval<const Vec3&>(), Real{}, Real{}))>>
    : std::true_type {};

template <typename A, typename B>
constexpr bool kCovered = HasPairFunction<A, B>::value || HasPairFunction<B, A>::value;

template <typename A, typename... Kinds>
constexpr bool coversRow(KindList<Kinds...>) {
  return (kCovered<A, Kinds> && ...);
}
template <typename... Kinds>
constexpr bool coversEveryPair(KindList<Kinds...> kinds) {
  return (coversRow<Kinds>(kinds) && ...);
}
template <typename... Kinds>
constexpr bool coversEveryPlane(KindList<Kinds...>) {
  return (HasPlaneFunction<Kinds>::value && ...);
}

}  // namespace narrowphase_detail

template <typename A, typename B>
Manifold collideShapes(const A& a, const Frame& fa, const B& b, const Frame& fb,
                       const Real margin) {
  if constexpr (narrowphase_detail::HasPairFunction<A, B>::value) {
    return collide(a, fa, b, fb, margin);
  } else {
    static_assert(narrowphase_detail::HasPairFunction<B, A>::value,
                  "no narrowphase pair function for these two body shape kinds");
    Manifold manifold = collide(b, fb, a, fa, margin);
    manifold.normal = -manifold.normal;
    return manifold;
  }
}

template <typename A>
Manifold collideWithPlaneShape(const A& a, const Frame& fa, const Vec3& normal, const Real offset,
                               const Real margin) {
  static_assert(narrowphase_detail::HasPlaneFunction<A>::value,
                "no narrowphase plane function for this body shape kind");
  return collideWithPlane(a, fa, normal, offset, margin);
}

static_assert(narrowphase_detail::coversEveryPair(BodyShapeKinds{}),
              "every ordered pair of BodyShapeKinds needs a narrowphase pair function "
              "(narrowphase.h): write collide(A, B) or collide(B, A)");
static_assert(narrowphase_detail::coversEveryPlane(BodyShapeKinds{}),
              "every BodyShapeKind needs collideWithPlane (narrowphase.h)");

}  // namespace engine
}  // namespace mass_aggregate_sim
