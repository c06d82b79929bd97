#include "engine/collision/narrowphase/point_reduction.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace mass_aggregate_sim {
namespace engine {
namespace {

// Twice the signed area of the triangle a, b, c seen along normal.
Real doubleArea(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& normal) {
  return (b - a).cross(c - a).dot(normal);
}

}  // namespace

void addReducedPoints(const ManifoldPoint* candidates, const int count, const Vec3& normal,
                      const Real depth_tolerance, Manifold& manifold) {
  if (count <= Manifold::kMaxPoints) {
    for (int i = 0; i < count; ++i) manifold.points[manifold.count++] = candidates[i];
    return;
  }
  // Index of the candidate with the largest score (the first of equals); -1 when none is > 0.
  const auto best = [&](const auto& score) {
    int chosen = -1;
    Real chosen_score = 0.0;
    for (int i = 0; i < count; ++i) {
      const Real s = score(candidates[i].point);
      if (s > chosen_score) {
        chosen = i;
        chosen_score = s;
      }
    }
    return chosen;
  };
  Real least = candidates[0].separation;
  for (int i = 1; i < count; ++i) least = std::min(least, candidates[i].separation);
  int deepest = 0;
  while (candidates[deepest].separation > least + depth_tolerance) ++deepest;
  manifold.points[manifold.count++] = candidates[deepest];
  const Vec3 p0 = candidates[deepest].point;
  const int far = best([&](const Vec3& p) { return (p - p0).squaredNorm(); });
  if (far < 0) return;
  manifold.points[manifold.count++] = candidates[far];
  const Vec3 p1 = candidates[far].point;
  const int wide = best([&](const Vec3& p) { return std::abs(doubleArea(p0, p1, p, normal)); });
  if (wide < 0) return;
  manifold.points[manifold.count++] = candidates[wide];
  const Vec3 p2 = candidates[wide].point;
  // A point outside the triangle adds the triangles it makes with the edges it sees.
  const Real orientation = doubleArea(p0, p1, p2, normal) > 0.0 ? 1.0 : -1.0;
  const int fourth = best([&](const Vec3& p) {
    return std::max(0.0, -orientation * doubleArea(p0, p1, p, normal)) +
           std::max(0.0, -orientation * doubleArea(p1, p2, p, normal)) +
           std::max(0.0, -orientation * doubleArea(p2, p0, p, normal));
  });
  if (fourth >= 0) manifold.points[manifold.count++] = candidates[fourth];
}

}  // namespace engine
}  // namespace mass_aggregate_sim
