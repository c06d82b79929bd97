#pragma once
// The energy guard's sums over the particles in the four-particle groups of simd.h, so that the
// pass that makes them vectorises. The fused semi-implicit Euler pass and
// accumulateParticleEnergies() add in the same order, so they give the same bits.

#include <cstddef>

#include "engine/core/simd.h"
#include "engine/world/particle_energies.h"
#include "mass_aggregate_sim/engine/core/types.h"

namespace mass_aggregate_sim {
namespace engine {

// sum m |v|^2 and sum m x (the gravitational energy is -g . sum m x), per lane of the groups.
struct EnergyAccumulator {
  simd::Real4 kinetic[3] = {};
  simd::Real4 moment[3] = {};
  Real tail_kinetic = 0.0;
  Real tail_moment[3] = {0.0, 0.0, 0.0};

  // Part `block` (0-2) of a group: masses m spread to match, positions x, velocities u.
  void addGroup(const int block, const simd::Real4 m, const simd::Real4 x, const simd::Real4 u) {
    kinetic[block] += m * (u * u);
    moment[block] += m * x;
  }
  // One particle past the last whole group.
  void addParticle(const Real m, const Real* x, const Real* u) {
    for (int c = 0; c < 3; ++c) {
      tail_kinetic += m * (u[c] * u[c]);
      tail_moment[c] += m * x[c];
    }
  }
  ParticleEnergies sums(const Real* g) const;
};

// The accumulator over n particles (SoA: mass[i], x and v with xyz of particle i at 3i).
void accumulateParticleEnergies(std::size_t n, const Real* mass, const Real* x, const Real* v,
                                EnergyAccumulator& energies);

}  // namespace engine
}  // namespace mass_aggregate_sim
