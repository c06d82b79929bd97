#include "engine/world/energy_accumulator.h"

namespace mass_aggregate_sim {
namespace engine {

ParticleEnergies EnergyAccumulator::sums(const Real* g) const {
  const simd::Real4 k = (kinetic[0] + kinetic[1]) + kinetic[2];
  const simd::Real4* const m = moment;
  // Lanes of moment[b] hold the components of simd::pattern<b>: (x y z x) (y z x y) (z x y z).
  const Real moment_x = ((m[0][0] + m[0][3]) + m[1][2]) + m[2][1] + tail_moment[0];
  const Real moment_y = ((m[0][1] + m[1][0]) + m[1][3]) + m[2][2] + tail_moment[1];
  const Real moment_z = ((m[0][2] + m[1][1]) + m[2][0]) + m[2][3] + tail_moment[2];
  ParticleEnergies energies;
  energies.kinetic_twice = ((k[0] + k[1]) + k[2]) + k[3] + tail_kinetic;
  // E_g = -sum m g.x = -g . sum m x
  energies.gravitational = -(g[0] * moment_x + g[1] * moment_y + g[2] * moment_z);
  return energies;
}

namespace {

// Inlined into the cloned function below (see finite_check.cpp).
inline __attribute__((always_inline)) void addGroups(const std::size_t n, const Real* mass,
                                                     const Real* x, const Real* v,
                                                     EnergyAccumulator& energies) {
  using simd::load;
  std::size_t i = 0;
  for (; i + 4 <= n; i += 4) {
    const simd::Real4 m = load(mass + i);
    const simd::Real4 spread[3] = {simd::spread0(m), simd::spread1(m), simd::spread2(m)};
    for (int b = 0; b < 3; ++b) {
      const std::size_t k = 3 * i + 4 * static_cast<std::size_t>(b);
      energies.addGroup(b, spread[b], load(x + k), load(v + k));
    }
  }
  for (; i < n; ++i) energies.addParticle(mass[i], x + 3 * i, v + 3 * i);
}

MAS_SIMD_CLONES void accumulateGroups(const std::size_t n, const Real* mass, const Real* x,
                                      const Real* v, EnergyAccumulator& energies) {
  addGroups(n, mass, x, v, energies);
}

}  // namespace

void accumulateParticleEnergies(const std::size_t n, const Real* mass, const Real* x, const Real* v,
                                EnergyAccumulator& energies) {
  accumulateGroups(n, mass, x, v, energies);
}

}  // namespace engine
}  // namespace mass_aggregate_sim
