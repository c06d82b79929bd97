#include "mass_aggregate_sim/engine/queries.h"

#include <cmath>

#include "mass_aggregate_sim/engine/shape_geometry.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

// Keeps the nearest hit so far and shortens the ray to it.
class NearestHit {
 public:
  NearestHit(const Vec3& origin, const Vec3& direction, const Real max_distance)
      : origin_(origin), direction_(direction), best_distance_(max_distance) {}
  Real reach() const { return best_distance_; }
  void offer(const std::optional<RayShapeHit>& hit, const bool particle, const ParticleId id,
             const ColliderId collider) {
    if (!hit || (found_ && hit->t >= best_distance_)) return;
    best_.hit_particle = particle;
    best_.particle = id;
    best_.collider = collider;
    best_.distance = hit->t;
    best_.point = origin_ + hit->t * direction_;
    best_.normal = hit->normal;
    best_distance_ = hit->t;
    found_ = true;
  }
  std::optional<RayHit> best() const {
    if (!found_) return std::nullopt;
    return best_;
  }

 private:
  Vec3 origin_;
  Vec3 direction_;
  Real best_distance_;  // max_distance until something is hit
  bool found_ = false;
  RayHit best_;
};

}  // namespace

std::optional<RayHit> raycastScene(const ParticleStore& particles, const Colliders& colliders,
                                   const Vec3& origin, const Vec3& direction,
                                   const Real max_distance) {
  const Real length = direction.norm();
  if (!origin.allFinite() || !std::isfinite(length) || length <= 0.0 || std::isnan(max_distance) ||
      max_distance < 0.0) {
    return std::nullopt;
  }
  const Vec3 d = direction / length;
  NearestHit nearest(origin, d, max_distance);
  for (const PlaneCollider& plane : colliders.planes) {
    nearest.offer(rayVsPlane(origin, d, nearest.reach(), plane, 0.0), false, ParticleId{},
                  plane.id);
  }
  for (const SphereCollider& sphere : colliders.spheres) {
    nearest.offer(rayVsSphere(origin, d, nearest.reach(), sphere.center, sphere.radius), false,
                  ParticleId{}, sphere.id);
  }
  for (const BoxCollider& box : colliders.boxes) {
    nearest.offer(rayVsBox(origin, d, nearest.reach(), box, 0.0), false, ParticleId{}, box.id);
  }
  for (const CapsuleCollider& capsule : colliders.capsules) {
    nearest.offer(rayVsCapsule(origin, d, nearest.reach(), capsule, 0.0), false, ParticleId{},
                  capsule.id);
  }
  const auto x = particles.positions();
  const auto radius = particles.radii();
  for (std::size_t i = 0; i < particles.size(); ++i) {
    nearest.offer(rayVsSphere(origin, d, nearest.reach(), x.col(i), radius[i]), true,
                  particles.idAt(i), 0);
  }
  return nearest.best();
}

std::vector<ParticleId> particlesOverlappingSphere(const ParticleStore& particles,
                                                   const Vec3& center, const Real radius) {
  std::vector<ParticleId> found;
  const auto x = particles.positions();
  const auto r = particles.radii();
  for (std::size_t i = 0; i < particles.size(); ++i) {
    const Real reach = radius + r[i];
    if ((x.col(i) - center).squaredNorm() <= reach * reach) found.push_back(particles.idAt(i));
  }
  return found;
}

std::vector<ParticleId> particlesOverlappingBox(const ParticleStore& particles, const Vec3& center,
                                                const Vec3& half_extents) {
  std::vector<ParticleId> found;
  const auto x = particles.positions();
  const auto r = particles.radii();
  for (std::size_t i = 0; i < particles.size(); ++i) {
    // Distance from the centre to the box: the part of |x - c| beyond the half extents per axis.
    const Vec3 outside = ((x.col(i) - center).cwiseAbs() - half_extents).cwiseMax(0.0);
    if (outside.squaredNorm() <= r[i] * r[i]) found.push_back(particles.idAt(i));
  }
  return found;
}

}  // namespace engine
}  // namespace mass_aggregate_sim
