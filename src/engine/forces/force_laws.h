#pragma once
// The force laws the force generators share, each written once: a spring's (particles' springs in
// their dense runs, springs on bodies' points), drag's and buoyancy's (on particles and on bodies),
// and the check of a buoyancy's liquid.

#include <cmath>

#include "mass_aggregate_sim/engine/core/status.h"
#include "mass_aggregate_sim/engine/core/types.h"

namespace mass_aggregate_sim {
namespace engine {

constexpr Real kMinSpringLength = 1e-12;

// Force on the first end of a spring from a to b (the second end gets the opposite), in scalars
// on raw columns so the hot loop has no temporaries; va, vb are read only when c != 0.
// With d = x_a - x_b, l = |d|, n = d / l: F_a = -(k (l - L) + c (v_a - v_b).n) n.
// `pull_only` makes it a bungee: nothing while l <= L. Returns false when there is no force.
// Takes l and 1/l computed by the caller (singly or a block at a time).
inline bool springForceFromLength(const Real* d, const Real length, const Real inverse_length,
                                  const Real* va, const Real* vb, const Real stiffness,
                                  const Real rest_length, const Real damping, const bool pull_only,
                                  Real* force) {
  if (length < kMinSpringLength) return false;
  const Real extension = length - rest_length;
  if (pull_only && extension <= 0.0) return false;
  // n = d * (1/l) differs from d / l only in the last bit, and costs one division, not three.
  const Real n[3] = {d[0] * inverse_length, d[1] * inverse_length, d[2] * inverse_length};
  Real damping_force = 0.0;
  if (damping != 0.0) {
    damping_force =
        damping * ((va[0] - vb[0]) * n[0] + (va[1] - vb[1]) * n[1] + (va[2] - vb[2]) * n[2]);
  }
  const Real magnitude = -(stiffness * extension + damping_force);
  force[0] = magnitude * n[0];
  force[1] = magnitude * n[1];
  force[2] = magnitude * n[2];
  return true;
}

inline bool springForce(const Real* xa, const Real* xb, const Real* va, const Real* vb,
                        const Real stiffness, const Real rest_length, const Real damping,
                        const bool pull_only, Real* force) {
  const Real d[3] = {xa[0] - xb[0], xa[1] - xb[1], xa[2] - xb[2]};
  const Real length = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  if (length < kMinSpringLength) return false;
  return springForceFromLength(d, length, 1.0 / length, va, vb, stiffness, rest_length, damping,
                               pull_only, force);
}

// A spring's pull along its line for an extension l - L: k (l - L), none for a slack bungee.
inline Real springTension(const Real extension, const Real stiffness, const bool pull_only) {
  return pull_only && extension <= 0.0 ? 0.0 : stiffness * extension;
}

// The liquid of a buoyancy: a density >= 0, a finite surface height, a non-zero up.
inline Status checkLiquid(const Real density, const Real surface_height, const Vec3& up) {
  if (!(std::isfinite(density) && density >= 0.0)) {
    return Status::error("liquid_density must be finite and >= 0");
  }
  if (!std::isfinite(surface_height)) return Status::error("surface_height is not finite");
  if (!up.allFinite() || up.norm() < 1e-9) {
    return Status::error("up must be a finite non-zero vector");
  }
  return Status::ok();
}

// F = -(k1 |v| + k2 |v|^2) v/|v| = -(k1 + k2 |v|) v
inline Vec3 dragForce(const Vec3& v, const Real k1, const Real k2) {
  return -(k1 + k2 * v.norm()) * v;
}

// The submerged fraction of a volume whose centre is at height s above a liquid's surface:
// 0 for s >= max_depth, 1 for s <= -max_depth, linear in between: (max_depth - s) / (2 max_depth).
// Buoyancy is then rho V |g| times it, along up.
inline Real submergedFraction(const Real height, const Real max_depth) {
  if (height >= max_depth) return 0.0;
  if (height <= -max_depth) return 1.0;
  return (max_depth - height) / (2.0 * max_depth);
}

}  // namespace engine
}  // namespace mass_aggregate_sim
