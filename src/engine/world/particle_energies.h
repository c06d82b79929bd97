#pragma once
// The energy guard's sums over the particles.

#include <cmath>

#include "mass_aggregate_sim/engine/core/types.h"

namespace mass_aggregate_sim {
namespace engine {

// Twice the kinetic energy and the gravitational energy (immovable particles count with mass 0).
// Not finite when a position or velocity is not: m u^2 and m x carry an Inf or NaN into the sums
// (0 * Inf is NaN), and finite values only overflow at absurd energies.
struct ParticleEnergies {
  Real kinetic_twice = 0.0;
  Real gravitational = 0.0;
  bool finite() const { return std::isfinite(kinetic_twice) && std::isfinite(gravitational); }
};

}  // namespace engine
}  // namespace mass_aggregate_sim
