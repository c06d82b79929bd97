#include "engine/bodies/body_motion.h"

#include <cmath>

namespace mass_aggregate_sim {
namespace engine {
namespace {

Mat3 skew(const Vec3& v) {
  Mat3 m;
  m << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return m;
}

}  // namespace

Quat rotationOver(const Vec3& w, const Real h) {
  const Real speed = w.norm();
  const Real half_angle = 0.5 * speed * h;
  // sin(half_angle) / speed, by its series where the division would lose digits.
  const Real scale = half_angle < 1e-4 ? 0.5 * h * (1.0 - half_angle * half_angle / 6.0)
                                       : std::sin(half_angle) / speed;
  return Quat(std::cos(half_angle), scale * w.x(), scale * w.y(), scale * w.z());
}

Quat firstOrderRotation(const Quat& q, const Vec3& w, const Real h) {
  // q' = q + h/2 (0, w) q
  const Quat spin = Quat(0.0, w.x(), w.y(), w.z()) * q;
  return Quat(q.coeffs() + 0.5 * h * spin.coeffs()).normalized();
}

Vec3 gyroscopicStep(const Vec3& w_body, const Vec3& inertia, const Real h) {
  const Mat3 i = inertia.asDiagonal();
  const Real scale = inertia.cwiseProduct(w_body).norm();
  Vec3 w = w_body;
  for (int iteration = 0; iteration < 8; ++iteration) {
    const Vec3 m = 0.5 * (w_body + w);
    const Vec3 l = i * m;
    const Vec3 residual = i * (w - w_body) + h * m.cross(l);
    if (residual.norm() <= 1e-15 * scale) break;
    const Mat3 jacobian = i + 0.5 * h * (skew(m) * i - skew(l));
    w -= jacobian.partialPivLu().solve(residual);
  }
  return w;
}

}  // namespace engine
}  // namespace mass_aggregate_sim
