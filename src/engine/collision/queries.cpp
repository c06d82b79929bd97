#include "mass_aggregate_sim/engine/collision/queries.h"

#include <cmath>

#include "engine/collision/geometry.h"

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
  colliders.forEach([&](const auto& shapes) {
    using Shape = typename std::decay_t<decltype(shapes)>::value_type;
    for (const Shape& shape : shapes) {
      nearest.offer(ShapeKind<Shape>::raycast(shape, origin, d, nearest.reach(), 0.0), false,
                    ParticleId{}, shape.id);
    }
  });
  const auto x = particles.positions();
  const auto radius = particles.radii();
  for (std::size_t i = 0; i < particles.size(); ++i) {
    nearest.offer(rayIntoBall(origin, d, nearest.reach(), x.col(i), radius[i]), true,
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
