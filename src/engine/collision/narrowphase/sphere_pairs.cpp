// The sphere's pair functions: against a sphere, a box and a capsule.
#include "engine/collision/geometry.h"
#include "engine/collision/narrowphase/contact_points.h"
#include "engine/collision/narrowphase/narrowphase.h"

namespace mass_aggregate_sim {
namespace engine {

Manifold collide(const SphereShape& a, const Frame& fa, const SphereShape& b, const Frame& fb,
                 const Real margin) {
  // Concentric: any direction separates them; B leaves upwards.
  return ballContact(fa.position, a.radius, fb.position, b.radius, margin, Vec3::UnitZ());
}

Manifold collide(const SphereShape& a, const Frame& fa, const BoxShape& b, const Frame& fb,
                 const Real margin) {
  Manifold manifold;
  const Vec3& h = b.half_extents;
  const Real r = a.radius;
  const Vec3 c = fb.applyInverse(fa.position);  // the sphere's centre in the box's frame
  const Vec3 q = c.cwiseMax(-h).cwiseMin(h);    // the box's nearest point
  const Vec3 out = c - q;
  const Real distance = out.norm();
  if (distance > kTinyLength) {
    const Real separation = distance - r;
    if (!(separation <= margin)) return manifold;
    const Vec3 o = out / distance;  // the box's outward normal towards the sphere
    manifold.normal = fb.rotation * (-o);
    // Surfaces at q and c - r o = q + (distance - r) o.
    addPoint(manifold, fb.apply(q + 0.5 * separation * o), separation, 0);
    return manifold;
  }
  // Centre inside: out through the nearest face, at depth to_face + r.
  const Vec3 to_face = h - c.cwiseAbs();
  Eigen::Index axis = 0;
  to_face.minCoeff(&axis);
  Vec3 o = Vec3::Zero();
  o[axis] = c[axis] >= 0.0 ? 1.0 : -1.0;
  const Real separation = -to_face[axis] - r;
  if (!(separation <= margin)) return manifold;
  manifold.normal = fb.rotation * (-o);
  // Surfaces at c - r o and on the face, c + to_face o.
  addPoint(manifold, fb.apply(c + 0.5 * (to_face[axis] - r) * o), separation, 0);
  return manifold;
}

Manifold collide(const SphereShape& a, const Frame& fa, const CapsuleShape& b, const Frame& fb,
                 const Real margin) {
  const Segment segment = capsuleSegment(b, fb);
  const Vec3 nearest =
      closestOnSegment(fa.position, segment.start, Vec3(segment.start + segment.axis));
  // Centre on the axis: the capsule leaves along its own x axis.
  return ballContact(fa.position, a.radius, nearest, b.radius, margin, fb.rotation.col(0));
}

}  // namespace engine
}  // namespace mass_aggregate_sim
