#pragma once
// The narrowphase: a pair function for every unordered pair of body shape kinds, for each kind
// against a half-space (a plane collider), and the dispatch that makes the table complete.
//
// Every pair function takes the two shapes at their world frames and a speculative margin, and
// returns the manifold (count 0 when the shapes are farther apart than margin). The normal points
// from the first shape to the second. A particle is a SphereShape of its radius at its position.
// The static colliders use the same functions: a SphereCollider is a SphereShape at its centre, a
// BoxCollider a BoxShape, a CapsuleCollider a CapsuleShape along its segment.

#include "engine/collision/narrowphase/manifold.h"
#include "mass_aggregate_sim/engine/bodies/body_shapes.h"

namespace mass_aggregate_sim {
namespace engine {

Manifold collide(const SphereShape& a, const Frame& fa, const SphereShape& b, const Frame& fb,
                 Real margin);
Manifold collide(const SphereShape& a, const Frame& fa, const BoxShape& b, const Frame& fb,
                 Real margin);
Manifold collide(const SphereShape& a, const Frame& fa, const CapsuleShape& b, const Frame& fb,
                 Real margin);
Manifold collide(const CapsuleShape& a, const Frame& fa, const CapsuleShape& b, const Frame& fb,
                 Real margin);
Manifold collide(const CapsuleShape& a, const Frame& fa, const BoxShape& b, const Frame& fb,
                 Real margin);
Manifold collide(const BoxShape& a, const Frame& fa, const BoxShape& b, const Frame& fb,
                 Real margin);

// The shape against the half-space {x : normal.x < offset} (normal unit); the manifold's normal
// points from the shape into the half-space (-normal).
Manifold collideWithPlane(const SphereShape& a, const Frame& fa, const Vec3& normal, Real offset,
                          Real margin);
Manifold collideWithPlane(const BoxShape& a, const Frame& fa, const Vec3& normal, Real offset,
                          Real margin);
Manifold collideWithPlane(const CapsuleShape& a, const Frame& fa, const Vec3& normal, Real offset,
                          Real margin);

}  // namespace engine
}  // namespace mass_aggregate_sim
