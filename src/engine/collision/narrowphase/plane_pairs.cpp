// Each body shape against a half-space {x : normal.x < offset}. A point at height d = normal.x -
// offset above the plane has separation d less the shape's radius there; the manifold's normal is
// -normal (from the shape into the half-space).
#include <array>

#include "engine/collision/narrowphase/box_features.h"
#include "engine/collision/narrowphase/contact_points.h"
#include "engine/collision/narrowphase/narrowphase.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

// A ball's point: its surface at centre - r n, the plane's at centre - (separation + r) n.
void addBallOnPlane(const Vec3& centre, const Real r, const Vec3& normal, const Real offset,
                    const Real margin, const std::uint32_t id, Manifold& manifold) {
  const Real separation = normal.dot(centre) - offset - r;
  if (separation <= margin) {
    addPoint(manifold, centre - (r + 0.5 * separation) * normal, separation, id);
  }
}

}  // namespace

Manifold collideWithPlane(const SphereShape& a, const Frame& fa, const Vec3& normal,
                          const Real offset, const Real margin) {
  Manifold manifold;
  manifold.normal = -normal;
  addBallOnPlane(fa.position, a.radius, normal, offset, margin, 0, manifold);
  return manifold;
}

// Ids: 0 for the end at local z = -half_length, 1 for the other.
Manifold collideWithPlane(const CapsuleShape& a, const Frame& fa, const Vec3& normal,
                          const Real offset, const Real margin) {
  Manifold manifold;
  manifold.normal = -normal;
  const Segment segment = capsuleSegment(a, fa);
  addBallOnPlane(segment.start, a.radius, normal, offset, margin, 0, manifold);
  addBallOnPlane(segment.start + segment.axis, a.radius, normal, offset, margin, 1, manifold);
  return manifold;
}

// The deepest four corners within margin (ties: the lower corner index); id = corner index.
Manifold collideWithPlane(const BoxShape& a, const Frame& fa, const Vec3& normal, const Real offset,
                          const Real margin) {
  Manifold manifold;
  manifold.normal = -normal;
  std::array<Vec3, 8> corners;
  std::array<Real, 8> separations;
  for (int c = 0; c < 8; ++c) {
    corners[c] = fa.apply(boxCorner(a.half_extents, c));
    separations[c] = normal.dot(corners[c]) - offset;
  }
  std::array<bool, 8> taken{};
  while (manifold.count < Manifold::kMaxPoints) {
    int deepest = -1;
    for (int c = 0; c < 8; ++c) {
      if (taken[c] || !(separations[c] <= margin)) continue;
      if (deepest < 0 || separations[c] < separations[deepest]) deepest = c;
    }
    if (deepest < 0) break;
    taken[deepest] = true;
    const Real separation = separations[deepest];
    addPoint(manifold, corners[deepest] - 0.5 * separation * normal, separation,
             static_cast<std::uint32_t>(deepest));
  }
  return manifold;
}

}  // namespace engine
}  // namespace mass_aggregate_sim
