#pragma once

#include <cmath>

#include "mass_aggregate_sim/engine/core/types.h"

namespace mass_aggregate_sim {
namespace engine {

// Particle damping d, the fraction of velocity kept per second, is the linear ODE term
// v' = lambda v with lambda = ln d. With a constant acceleration a beside it, v' = lambda v + a has
// the exact solution over a time t
//   v(t) = e^(lambda t) v0 + phi(t) a,   phi(t) = (e^(lambda t) - 1) / lambda,
// phi(t) = t without damping (d = 1) and 0 when no velocity is kept at all (d = 0). The
// integrators of order two and four build their damping from this flow, so it costs them no order.
struct DampingFlow {
  Real decay = 1.0;  // e^(lambda t) = d^t
  Real gain = 0.0;   // phi(t)
};

inline DampingFlow dampingFlow(const Real damping, const Real t) {
  if (damping >= 1.0) return {1.0, t};
  if (damping <= 0.0) return {0.0, 0.0};
  const Real lambda = std::log(damping);
  // expm1 keeps phi accurate when lambda t is small
  return {std::pow(damping, t), std::expm1(lambda * t) / lambda};
}

}  // namespace engine
}  // namespace mass_aggregate_sim
