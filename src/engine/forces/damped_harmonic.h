#pragma once

#include <cmath>

#include "mass_aggregate_sim/engine/core/types.h"

namespace mass_aggregate_sim {
namespace engine {

struct HarmonicState {
  Vec3 position = Vec3::Zero();
  Vec3 velocity = Vec3::Zero();
};

// The exact damped harmonic motion of x'' = -w2 x - 2 beta x' from (x0, v0) over t:
//   x(t) = e^(-beta t) (x0 C(t) + (v0 + beta x0) S(t)),
//   v(t) = -beta x(t) + e^(-beta t) (-g^2 x0 S(t) + (v0 + beta x0) C(t)),
// with g^2 = w2 - beta^2 and C, S = cos(g t), sin(g t) / g when underdamped, cosh, sinh / g when
// overdamped, 1, t at critical damping (C' = -g^2 S and S' = C in all three).
inline HarmonicState dampedHarmonicMotion(const Vec3& x0, const Vec3& v0, const Real w2,
                                          const Real beta, const Real t) {
  const Real g2 = w2 - beta * beta;
  Real c;
  Real s;
  if (std::abs(g2) * t * t < 1e-12) {
    c = 1.0;
    s = t;
  } else if (g2 > 0.0) {
    const Real g = std::sqrt(g2);
    c = std::cos(g * t);
    s = std::sin(g * t) / g;
  } else {
    const Real g = std::sqrt(-g2);
    c = std::cosh(g * t);
    s = std::sinh(g * t) / g;
  }
  const Real decay = std::exp(-beta * t);
  const Vec3 lead = v0 + beta * x0;
  HarmonicState state;
  state.position = decay * (x0 * c + lead * s);
  state.velocity = -beta * state.position + decay * (lead * c - g2 * s * x0);
  return state;
}

}  // namespace engine
}  // namespace mass_aggregate_sim
