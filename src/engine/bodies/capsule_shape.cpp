// The capsule body shape kind (capsule_shape.h).
#include "mass_aggregate_sim/engine/bodies/capsule_shape.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "engine/collision/geometry.h"
#include "engine/core/checks.h"

namespace mass_aggregate_sim {
namespace engine {

Status BodyShapeKind<CapsuleShape>::validate(const CapsuleShape& capsule) {
  if (!finitePositive(capsule.radius)) {
    return Status::error("capsule radius must be finite and > 0");
  }
  if (!finitePositive(capsule.half_length)) {
    return Status::error("capsule half_length must be finite and > 0");
  }
  return Status::ok();
}

Real BodyShapeKind<CapsuleShape>::volume(const CapsuleShape& capsule) {
  const Real r = capsule.radius;
  return M_PI * r * r * (2.0 * capsule.half_length + 4.0 / 3.0 * r);
}

// Cylinder (mass m_c, height 2h): I_z = m_c r^2 / 2, I_x = m_c (3 r^2 + 4 h^2) / 12.
// Each hemisphere (mass m_h = 2/3 pi r^3): I_z = 2/5 m_h r^2; about a transverse axis through its
// flat face also 2/5 m_h r^2. Its centroid lies 3r/8 from that face, so moving the axis to the
// centroid and then to the capsule's centre (h + 3r/8 away) gives
// 2/5 m_h r^2 - m_h (3r/8)^2 + m_h (h + 3r/8)^2 = m_h (2/5 r^2 + h^2 + 3/4 h r).
Vec3 BodyShapeKind<CapsuleShape>::unitInertia(const CapsuleShape& capsule) {
  const Real r = capsule.radius;
  const Real h = capsule.half_length;
  const Real cylinder = M_PI * r * r * 2.0 * h;
  const Real hemisphere = 2.0 / 3.0 * M_PI * r * r * r;
  const Real axial = 0.5 * cylinder * r * r + 2.0 * 0.4 * hemisphere * r * r;
  const Real transverse = cylinder * (3.0 * r * r + 4.0 * h * h) / 12.0 +
                          2.0 * hemisphere * (0.4 * r * r + h * h + 0.75 * h * r);
  return Vec3(transverse, transverse, axial);
}

Aabb BodyShapeKind<CapsuleShape>::aabb(const CapsuleShape& capsule, const Frame& frame) {
  const Vec3 extent =
      frame.rotation.col(2).cwiseAbs() * capsule.half_length + Vec3::Constant(capsule.radius);
  return Aabb{frame.position - extent, frame.position + extent};
}

std::optional<RayShapeHit> BodyShapeKind<CapsuleShape>::raycast(const CapsuleShape& capsule,
                                                                const Frame& frame,
                                                                const Vec3& origin,
                                                                const Vec3& direction,
                                                                const Real max_t) {
  const Vec3 half_axis = frame.rotation.col(2) * capsule.half_length;
  return rayIntoCapsule(origin, direction, max_t, frame.position - half_axis,
                        frame.position + half_axis, capsule.radius);
}

std::vector<ShapePrimitive> BodyShapeKind<CapsuleShape>::describe(const CapsuleShape& capsule) {
  const Real diameter = 2.0 * capsule.radius;
  std::vector<ShapePrimitive> parts(3);
  parts[0].type = ShapePrimitive::Type::kCylinder;
  parts[0].size = Vec3(diameter, diameter, 2.0 * capsule.half_length);
  for (int end = 0; end < 2; ++end) {
    ShapePrimitive& ball = parts[1 + end];
    ball.type = ShapePrimitive::Type::kSphere;
    ball.center = Vec3(0.0, 0.0, end == 0 ? -capsule.half_length : capsule.half_length);
    ball.size = Vec3::Constant(diameter);
  }
  return parts;
}

namespace {

// The part below the surface of a disk of radius rho whose centre is h above the surface, the
// disk's plane tilted so that its height rises by `tilt` per metre along its steepest direction
// e (tilt = sin of the angle between the capsule's axis and up): the points eta e + ... with
// h + tilt eta < 0, the disk below the chord at eta0 = -h / tilt. The segment beyond a chord at
// distance d from the centre has half-angle alpha = atan2(c, d), c = sqrt((rho - d)(rho + d)),
// and area rho^2 alpha - c d (acos(d / rho) would lose all its digits near a grazing cut); the
// part below eta0 is that segment (d = -eta0) or the disk without it (d = eta0), and its first
// moment along e is -2/3 c^3.
struct DiskPart {
  Real area = 0.0;
  Real moment = 0.0;
};
DiskPart diskBelow(const Real rho, const Real h, const Real tilt) {
  if (rho <= 0.0) return DiskPart{};
  if (std::abs(h) >= tilt * rho) return h < 0.0 ? DiskPart{M_PI * rho * rho, 0.0} : DiskPart{};
  const Real eta0 = -h / tilt;
  const Real d = std::min(std::abs(eta0), rho);
  const Real chord = std::sqrt((rho - d) * (rho + d));
  const Real segment = std::max(rho * rho * std::atan2(chord, d) - chord * d, 0.0);
  const Real area = eta0 < 0.0 ? segment : M_PI * rho * rho - segment;
  return DiskPart{area, -2.0 / 3.0 * chord * chord * chord};
}

// Gauss-Legendre nodes and weights, 8 points on [-1, 1] (symmetric pairs).
constexpr Real kNode[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267,
                           0.9602898564975363};
constexpr Real kWeight[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745,
                             0.1012285362903763};

// The disks along a piece of the capsule's axis, x(t) = base + t axis for t in [t0, t1] (radius
// rho(t), centre height above(t) = h_base + t c): sum of their parts below the surface, where the
// cut moves smoothly through the disks (the caller splits the axis where it enters or leaves a
// disk). The substitution t = t0 + (t1 - t0) (3u^2 - 2u^3) flattens the integrand's ends, where
// a segment's area behaves as a power 3/2 of the distance, so the quadrature keeps its order.
template <typename Radius>
void addDisks(const Vec3& base, const Vec3& axis, const Vec3& e, const Real h_base, const Real c,
              const Real tilt, const Real t0, const Real t1, Radius&& rho, SubmergedVolume& sum) {
  if (t1 <= t0) return;
  for (int n = 0; n < 8; ++n) {
    const Real node = (n < 4 ? -1.0 : 1.0) * kNode[n % 4];
    const Real u = 0.5 * (node + 1.0);
    const Real t = t0 + (t1 - t0) * u * u * (3.0 - 2.0 * u);
    const Real dt = (t1 - t0) * 6.0 * u * (1.0 - u) * 0.5 * kWeight[n % 4];
    const DiskPart part = diskBelow(rho(t), h_base + t * c, tilt);
    sum.volume += dt * part.area;
    sum.moment += dt * (part.area * (base + t * axis) + part.moment * e);
  }
}

// Splits [t0, t1] at the given points (those inside) and adds the disks of each piece.
template <typename Radius>
void addSplitDisks(const Vec3& base, const Vec3& axis, const Vec3& e, const Real h_base,
                   const Real c, const Real tilt, const Real t0, const Real t1, Real cut_a,
                   Real cut_b, Radius&& rho, SubmergedVolume& sum) {
  if (cut_b < cut_a) std::swap(cut_a, cut_b);
  Real from = t0;
  for (const Real cut : {cut_a, cut_b}) {
    if (!(cut > from && cut < t1)) continue;
    addDisks(base, axis, e, h_base, c, tilt, from, cut, rho, sum);
    from = cut;
  }
  addDisks(base, axis, e, h_base, c, tilt, from, t1, rho, sum);
}

}  // namespace

// The capsule as disks across its axis a: the cylinder's of radius r for t in [-l, l], each
// hemisphere's of radius sqrt(r^2 - t^2) at t in [0, r] beyond its end. A disk at height h is cut
// by the surface where |h| < tilt rho (diskBelow); along the cylinder that starts and stops at
// h_c + t c = +-tilt r (c = up.a), and beyond an end at height h_e (outward direction a', c' =
// up.a') where (h_e + t c')^2 = (r^2 - t^2) tilt^2: t = -h_e c' +- tilt sqrt(r^2 - h_e^2).
SubmergedVolume BodyShapeKind<CapsuleShape>::submerged(const CapsuleShape& capsule,
                                                       const Frame& frame,
                                                       const LiquidSurface& surface) {
  const Real r = capsule.radius;
  const Real l = capsule.half_length;
  const Vec3 axis = frame.rotation.col(2);
  const Real c = surface.up.dot(axis);
  const Real h_c = surface.above(frame.position);
  if (h_c >= l * std::abs(c) + r) return SubmergedVolume{};
  if (h_c <= -(l * std::abs(c) + r)) return SubmergedVolume::whole(volume(capsule), frame.position);
  const Vec3 rising = surface.up - c * axis;
  const Real tilt = rising.norm();
  const Vec3 e = tilt > 0.0 ? Vec3(rising / tilt) : Vec3::Zero();
  SubmergedVolume sum;
  const auto cylinder = [r](Real) { return r; };
  const auto cylinder_cut = [&](const Real side) {
    return c != 0.0 ? (side * tilt * r - h_c) / c : -2.0 * l;
  };
  addSplitDisks(frame.position, axis, e, h_c, c, tilt, -l, l, cylinder_cut(-1.0), cylinder_cut(1.0),
                cylinder, sum);
  const auto hemisphere = [r](const Real t) { return std::sqrt(std::max(r * r - t * t, 0.0)); };
  for (const Real side : {-1.0, 1.0}) {
    const Vec3 out = side * axis;
    const Vec3 end = frame.position + l * out;
    const Real h_e = surface.above(end);
    const Real c_e = side * c;
    const Real spread = tilt * std::sqrt(std::max(r * r - h_e * h_e, 0.0));
    addSplitDisks(end, out, e, h_e, c_e, tilt, 0.0, r, -h_e * c_e - spread, -h_e * c_e + spread,
                  hemisphere, sum);
  }
  return sum;
}

}  // namespace engine
}  // namespace mass_aggregate_sim
