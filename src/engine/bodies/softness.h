#pragma once
// Soft constraints (Box2D v3's "soft step"): a constraint row acts as a damped spring of frequency
// f and damping ratio zeta towards zero error, solved implicitly over the substep h. With
// omega = 2 pi f, the row's impulse is
//   j = -m_eff mass_scale (v + bias_rate C) - impulse_scale j_total
// where, from the implicit spring-damper (k = m omega^2, c = 2 m zeta omega):
//   bias_rate = omega / (2 zeta + h omega),
//   mass_scale = h omega (2 zeta + h omega) / (1 + h omega (2 zeta + h omega)),
//   impulse_scale = 1 / (1 + h omega (2 zeta + h omega)).
// f = 0 is a rigid row (no bias, full mass, no impulse feedback).

#include <cmath>

#include "mass_aggregate_sim/engine/core/types.h"

namespace mass_aggregate_sim {
namespace engine {

struct Softness {
  Real bias_rate = 0.0;
  Real mass_scale = 1.0;
  Real impulse_scale = 0.0;
};

inline Softness makeSoft(const Real hertz, const Real zeta, const Real h) {
  if (hertz == 0.0) return Softness{};
  const Real omega = 2.0 * M_PI * hertz;
  const Real a1 = 2.0 * zeta + h * omega;
  const Real a2 = h * omega * a1;
  const Real a3 = 1.0 / (1.0 + a2);
  return Softness{omega / a1, a2 * a3, a3};
}

}  // namespace engine
}  // namespace mass_aggregate_sim
