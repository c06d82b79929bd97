#pragma once
// The semi-implicit Euler update of all particles in one pass (World::integrateSemiImplicitEuler).

#include <cstddef>

#include "engine/world/energy_accumulator.h"
#include "mass_aggregate_sim/engine/core/types.h"

namespace mass_aggregate_sim {
namespace engine {

// Per-particle inputs, SoA: xyz of particle i at 3i, scalars at i.
struct SemiImplicitInputs {
  std::size_t count = 0;
  Real h = 0.0;
  const Real* gravity = nullptr;  // 3 values
  const Real* inverse_mass = nullptr;
  const Real* mobility = nullptr;  // 1 movable, 0 immovable
  // xyz; nullptr when every particle's is (+0, +0, +0) (ParticleStore::anyOwnAcceleration), so the
  // pass adds a constant +0 instead of reading them: the same bits.
  const Real* own_acceleration = nullptr;
  const Real* damping_factor = nullptr;  // d^h
  const Real* mass = nullptr;            // read only with `energies`
};

// What the pass measures of the state it writes, for the step's divergence check when nothing
// moves the particles after it.
enum class PassMeasure {
  kNothing,
  kEnergies,     // the energy guard's sums (which are finite only when the state is)
  kFiniteProbe,  // whether every new x and v is finite (allFinite(), made as they are written)
};

struct PassMeasurements {
  EnergyAccumulator energies;  // kEnergies: the new state added (accumulateParticleEnergies' order)
  bool all_finite = true;      // kFiniteProbe
};

// a = F/m + mobility (g + a_own) (F read from `a` when has_forces, else 0); v' = (v + a h) d^h;
// x' = x + v' h. `a` is stored only when keep_acceleration (a stage after the pass reads it);
// otherwise it is left as it was (the forces, when has_forces).
void semiImplicitEulerPass(const SemiImplicitInputs& in, bool has_forces, bool keep_acceleration,
                           Real* a, Real* x, Real* v, PassMeasure measure, PassMeasurements& out);

}  // namespace engine
}  // namespace mass_aggregate_sim
