#include "engine/collision/narrowphase/segment_closest.h"

#include <algorithm>

namespace mass_aggregate_sim {
namespace engine {
namespace {

constexpr Real kTinySquared = 1e-24;
// sin^2 of the angle below which two segments are treated as parallel.
constexpr Real kParallelSineSquared = 1e-12;

Real unitClamp(const Real x) { return std::clamp(x, Real{0.0}, Real{1.0}); }

}  // namespace

// Minimise |r + s d1 - t d2|^2 with r = p1 - p2, a = d1.d1, b = d1.d2, c = d1.r, e = d2.d2,
// f = d2.r. Setting the derivatives to zero: a s - b t + c = 0 and b s - e t + f = 0, so
// t = (b s + f) / e and s = (b f - c e) / (a e - b^2). When t falls outside [0, 1] it is clamped
// and s re-solved from the first equation for that t.
SegmentParameters closestSegmentParameters(const Vec3& p1, const Vec3& d1, const Vec3& p2,
                                           const Vec3& d2) {
  const Vec3 r = p1 - p2;
  const Real a = d1.squaredNorm();
  const Real e = d2.squaredNorm();
  const Real f = d2.dot(r);
  if (a <= kTinySquared && e <= kTinySquared) return {0.0, 0.0};
  if (a <= kTinySquared) return {0.0, unitClamp(f / e)};
  const Real c = d1.dot(r);
  if (e <= kTinySquared) return {unitClamp(-c / a), 0.0};
  const Real b = d1.dot(d2);
  const Real denominator = a * e - b * b;  // |d1 x d2|^2
  Real s =
      denominator > kParallelSineSquared * a * e ? unitClamp((b * f - c * e) / denominator) : 0.0;
  Real t = (b * s + f) / e;
  if (t < 0.0) {
    t = 0.0;
    s = unitClamp(-c / a);
  } else if (t > 1.0) {
    t = 1.0;
    s = unitClamp((b - c) / a);
  }
  return {s, t};
}

}  // namespace engine
}  // namespace mass_aggregate_sim
