#include "engine/integrators/semi_implicit_pass.h"

#include "engine/core/simd.h"
#include "engine/forces/particle_acceleration.h"
#include "engine/world/finite_check.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

using simd::Real4;

// Four particles (three Real4) per iteration, the rest one component at a time with the same
// operations in the same order, so every particle gets the same bits either way. Without kOwn
// and kKeep a particle costs the bytes of x, v, mobility and d^h alone (the floor's).
template <bool kHasForces, bool kOwn, bool kKeep, PassMeasure kMeasure>
inline __attribute__((always_inline)) void pass(const SemiImplicitInputs& in, Real* __restrict a,
                                                Real* __restrict x, Real* __restrict v,
                                                PassMeasurements& out) {
  constexpr bool kEnergies = kMeasure == PassMeasure::kEnergies;
  constexpr bool kProbe = kMeasure == PassMeasure::kFiniteProbe;
  using simd::load;
  using simd::store;
  Real4 probe = simd::broadcast(0.0);
  Real probe_tail = 0.0;
  const Real* const g = in.gravity;
  const Real4 h = simd::broadcast(in.h);
  const Real4 gravity[3] = {simd::pattern0(g), simd::pattern1(g), simd::pattern2(g)};
  const Real4 no_own = simd::broadcast(0.0);
  const auto spread = [](const Real4 s, const int b) {
    return b == 0 ? simd::spread0(s) : b == 1 ? simd::spread1(s) : simd::spread2(s);
  };
  std::size_t i = 0;
  for (; i + 4 <= in.count; i += 4) {
    const Real4 inverse_mass = load(in.inverse_mass + i);
    const Real4 mobility = load(in.mobility + i);
    const Real4 damping = load(in.damping_factor + i);
    const Real4 mass = kEnergies ? load(in.mass + i) : Real4{};
    for (int b = 0; b < 3; ++b) {
      const std::size_t k = 3 * i + 4 * static_cast<std::size_t>(b);
      const Real4 own = kOwn ? load(in.own_acceleration + k) : no_own;
      const Real4 uniform = uniformAcceleration(spread(mobility, b), gravity[b], own);
      const Real4 acceleration =
          kHasForces ? particleAcceleration(load(a + k), spread(inverse_mass, b), uniform)
                     : uniform;
      if constexpr (kKeep) store(a + k, acceleration);
      // v' = (v + a h) d^h,  x' = x + v' h
      const Real4 velocity = (load(v + k) + acceleration * h) * spread(damping, b);
      store(v + k, velocity);
      const Real4 position = load(x + k) + velocity * h;
      store(x + k, position);
      if constexpr (kEnergies) out.energies.addGroup(b, spread(mass, b), position, velocity);
      if constexpr (kProbe) probe += finiteProbeTerm(position, velocity);
    }
  }
  for (; i < in.count; ++i) {
    for (std::size_t c = 0; c < 3; ++c) {
      const std::size_t k = 3 * i + c;
      const Real own = kOwn ? in.own_acceleration[k] : 0.0;
      const Real uniform = uniformAcceleration(in.mobility[i], g[c], own);
      const Real acceleration =
          kHasForces ? particleAcceleration(a[k], in.inverse_mass[i], uniform) : uniform;
      if constexpr (kKeep) a[k] = acceleration;
      const Real velocity = (v[k] + acceleration * in.h) * in.damping_factor[i];
      v[k] = velocity;
      x[k] += velocity * in.h;
      if constexpr (kProbe) probe_tail += finiteProbeTerm(x[k], velocity);
    }
    if constexpr (kEnergies) out.energies.addParticle(in.mass[i], x + 3 * i, v + 3 * i);
  }
  if constexpr (kProbe) {
    out.all_finite = probedFinite(probe, probe_tail);
  }
}

template <bool kHasForces, bool kOwn, bool kKeep>
inline __attribute__((always_inline)) void measuredPass(const SemiImplicitInputs& in, Real* a,
                                                        Real* x, Real* v, const PassMeasure measure,
                                                        PassMeasurements& out) {
  switch (measure) {
    case PassMeasure::kNothing:
      return pass<kHasForces, kOwn, kKeep, PassMeasure::kNothing>(in, a, x, v, out);
    case PassMeasure::kEnergies:
      return pass<kHasForces, kOwn, kKeep, PassMeasure::kEnergies>(in, a, x, v, out);
    case PassMeasure::kFiniteProbe:
      return pass<kHasForces, kOwn, kKeep, PassMeasure::kFiniteProbe>(in, a, x, v, out);
  }
}

template <bool kHasForces, bool kOwn>
inline __attribute__((always_inline)) void keptPass(const SemiImplicitInputs& in, const bool keep,
                                                    Real* a, Real* x, Real* v,
                                                    const PassMeasure measure,
                                                    PassMeasurements& out) {
  if (keep) {
    measuredPass<kHasForces, kOwn, true>(in, a, x, v, measure, out);
  } else {
    measuredPass<kHasForces, kOwn, false>(in, a, x, v, measure, out);
  }
}

template <bool kHasForces>
inline __attribute__((always_inline)) void ownPass(const SemiImplicitInputs& in, const bool keep,
                                                   Real* a, Real* x, Real* v,
                                                   const PassMeasure measure,
                                                   PassMeasurements& out) {
  if (in.own_acceleration != nullptr) {
    keptPass<kHasForces, true>(in, keep, a, x, v, measure, out);
  } else {
    keptPass<kHasForces, false>(in, keep, a, x, v, measure, out);
  }
}

MAS_SIMD_CLONES void dispatch(const SemiImplicitInputs& in, const bool has_forces, const bool keep,
                              Real* a, Real* x, Real* v, const PassMeasure measure,
                              PassMeasurements& out) {
  PassMeasurements local;  // so the sums stay in registers
  if (has_forces) {
    ownPass<true>(in, keep, a, x, v, measure, local);
  } else {
    ownPass<false>(in, keep, a, x, v, measure, local);
  }
  out = local;
}

}  // namespace

void semiImplicitEulerPass(const SemiImplicitInputs& in, const bool has_forces,
                           const bool keep_acceleration, Real* a, Real* x, Real* v,
                           const PassMeasure measure, PassMeasurements& out) {
  dispatch(in, has_forces, keep_acceleration, a, x, v, measure, out);
}

}  // namespace engine
}  // namespace mass_aggregate_sim
