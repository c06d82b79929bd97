#include "mass_aggregate_sim/engine/force_evaluation.h"

#include <algorithm>
#include <cmath>

namespace mass_aggregate_sim {
namespace engine {
namespace {

constexpr Real kMinLength = 1e-12;

// Force on the first end of a spring from a to b (the second end gets the opposite), in scalars
// on raw columns so the hot loop has no temporaries; va, vb are read only when c != 0.
// With d = x_a - x_b, l = |d|, n = d / l: F_a = -(k (l - L) + c (v_a - v_b).n) n.
// `pull_only` makes it a bungee: nothing while l <= L. Returns false when there is no force.
// Takes l and 1/l computed by the caller (singly or a block at a time).
inline bool springForceFromLength(const Real* d, const Real length, const Real inverse_length,
                                  const Real* va, const Real* vb, const Real stiffness,
                                  const Real rest_length, const Real damping, const bool pull_only,
                                  Real* force) {
  if (length < kMinLength) return false;
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
  if (length < kMinLength) return false;
  return springForceFromLength(d, length, 1.0 / length, va, vb, stiffness, rest_length, damping,
                               pull_only, force);
}

// Pointer to column i of a 3 x N array that may have an outer stride.
template <typename Array>
inline auto column(Array& array, const std::size_t i) {
  return array.data() + static_cast<Eigen::Index>(i) * array.outerStride();
}

template <typename Pair>
void accumulatePairForces(const std::vector<Pair>& pairs, const ParticleStore& particles,
                          const Eigen::Ref<const Vec3Array>& x,
                          const Eigen::Ref<const Vec3Array>& v, const bool pull_only,
                          Eigen::Ref<Vec3Array> force) {
  for (const Pair& pair : pairs) {
    const std::size_t a = particles.denseIndexUnchecked(pair.a);
    const std::size_t b = particles.denseIndexUnchecked(pair.b);
    Real f[3];
    if (!springForce(column(x, a), column(x, b), column(v, a), column(v, b), pair.stiffness,
                     pair.rest_length, pair.damping, pull_only, f)) {
      continue;
    }
    Real* const fa = column(force, a);
    Real* const fb = column(force, b);
    for (int c = 0; c < 3; ++c) {
      fa[c] += f[c];
      fb[c] -= f[c];
    }
  }
}

// Dense springs a block at a time: gather d = x_a - x_b, then l = sqrt(d.d) and 1/l for the
// whole block with Eigen's packet operations (IEEE sqrt and division, the same bits as the scalar
// ones, several per instruction), then the forces.
constexpr Eigen::Index kBlock = 64;
using BlockArray = Eigen::Array<Real, kBlock, 1>;

template <typename Positions>
inline void gatherBlock(const DenseSpring* block, const Eigen::Index m, const Positions& x,
                        Real (*d)[3], BlockArray& squared) {
  for (Eigen::Index j = 0; j < m; ++j) {
    const Real* const xa = column(x, block[j].a);
    const Real* const xb = column(x, block[j].b);
    Real* const dj = d[j];
    dj[0] = xa[0] - xb[0];
    dj[1] = xa[1] - xb[1];
    dj[2] = xa[2] - xb[2];
    squared[j] = dj[0] * dj[0] + dj[1] * dj[1] + dj[2] * dj[2];
  }
}

// With `energy`, also adds k (l - L)^2 / 2 of every spring (stretched ones only when pull_only)
// to it, in order: the same sum addDensePairEnergy makes.
void accumulateDensePairForces(const std::vector<DenseSpring>& springs,
                               const Eigen::Ref<const Vec3Array>& x,
                               const Eigen::Ref<const Vec3Array>& v, const bool pull_only,
                               Eigen::Ref<Vec3Array> force, Real* energy) {
  Real d[kBlock][3];
  BlockArray squared;
  BlockArray length;
  BlockArray inverse_length;
  const auto count = static_cast<Eigen::Index>(springs.size());
  for (Eigen::Index start = 0; start < count; start += kBlock) {
    const Eigen::Index m = std::min(kBlock, count - start);
    const DenseSpring* const block = springs.data() + start;
    gatherBlock(block, m, x, d, squared);
    length.head(m) = squared.head(m).sqrt();
    inverse_length.head(m) = length.head(m).inverse();
    if (energy) {
      for (Eigen::Index j = 0; j < m; ++j) {
        const Real extension = length[j] - block[j].rest_length;
        if (pull_only && extension <= 0.0) continue;
        *energy += 0.5 * block[j].stiffness * extension * extension;
      }
    }
    for (Eigen::Index j = 0; j < m; ++j) {
      const DenseSpring& s = block[j];
      Real f[3];
      if (!springForceFromLength(d[j], length[j], inverse_length[j], column(v, s.a), column(v, s.b),
                                 s.stiffness, s.rest_length, s.damping, pull_only, f)) {
        continue;
      }
      Real* const fa = column(force, s.a);
      Real* const fb = column(force, s.b);
      for (int c = 0; c < 3; ++c) {
        fa[c] += f[c];
        fb[c] -= f[c];
      }
    }
  }
}

// energy + sum k (l - L)^2 / 2 over dense springs (stretched ones only when pull_only), summed in
// order.
Real addDensePairEnergy(Real energy, const std::vector<DenseSpring>& springs, const ConstVec3Map& x,
                        const bool pull_only) {
  Real d[kBlock][3];
  BlockArray squared;
  BlockArray length;
  const auto count = static_cast<Eigen::Index>(springs.size());
  for (Eigen::Index start = 0; start < count; start += kBlock) {
    const Eigen::Index m = std::min(kBlock, count - start);
    const DenseSpring* const block = springs.data() + start;
    gatherBlock(block, m, x, d, squared);
    length.head(m) = squared.head(m).sqrt();
    for (Eigen::Index j = 0; j < m; ++j) {
      const Real extension = length[j] - block[j].rest_length;
      if (pull_only && extension <= 0.0) continue;
      energy += 0.5 * block[j].stiffness * extension * extension;
    }
  }
  return energy;
}

template <typename Anchored>
void accumulateAnchoredForces(const std::vector<Anchored>& springs, const ParticleStore& particles,
                              const Eigen::Ref<const Vec3Array>& x,
                              const Eigen::Ref<const Vec3Array>& v, const bool pull_only,
                              Eigen::Ref<Vec3Array> force) {
  const Real at_rest[3] = {0.0, 0.0, 0.0};
  for (const Anchored& spring : springs) {
    const std::size_t i = particles.denseIndexUnchecked(spring.particle);
    Real f[3];
    if (!springForce(column(x, i), spring.anchor.data(), column(v, i), at_rest, spring.stiffness,
                     spring.rest_length, spring.damping, pull_only, f)) {
      continue;
    }
    Real* const fi = column(force, i);
    for (int c = 0; c < 3; ++c) fi[c] += f[c];
  }
}

// The exact damped harmonic motion of x'' = -w2 x - 2 beta x' (w2 = k/m, beta = c/(2m)) over t:
//   x(t) = e^(-beta t) (x0 C(t) + (v0 + beta x0) S(t)),
// where C, S are cos(g t), sin(g t)/g with g^2 = w2 - beta^2 (underdamped), their hyperbolic
// counterparts when g^2 < 0, and 1, t at critical damping.
inline Vec3 dampedHarmonicPosition(const Vec3& x0, const Vec3& v0, const Real w2, const Real beta,
                                   const Real t) {
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
  return std::exp(-beta * t) * (x0 * c + (v0 + beta * x0) * s);
}

// Elastic energy of the generators that are not springs between two particles (anchored springs
// and bungees, stiff springs), at positions x.
Real nonPairPotentialEnergy(const ForceGenerators& generators, const ParticleStore& particles,
                            const Eigen::Ref<const Vec3Array>& x) {
  const auto index = [&particles](const ParticleId id) {
    return particles.denseIndexUnchecked(id);
  };
  const auto elastic = [](const Real stiffness, const Real extension) {
    return 0.5 * stiffness * extension * extension;
  };
  Real energy = 0.0;
  for (const AnchoredSpring& s : generators.anchored_springs) {
    energy += elastic(s.stiffness, (x.col(index(s.particle)) - s.anchor).norm() - s.rest_length);
  }
  for (const AnchoredBungee& s : generators.anchored_bungees) {
    const Real extension = (x.col(index(s.particle)) - s.anchor).norm() - s.rest_length;
    if (extension > 0.0) energy += elastic(s.stiffness, extension);
  }
  for (const StiffSpring& s : generators.stiff_springs) {
    energy += elastic(s.stiffness, (x.col(index(s.particle)) - s.anchor).norm());
  }
  return energy;
}

}  // namespace

void accumulateGeneratorForces(const ForceGenerators& generators, const ParticleStore& particles,
                               const Eigen::Ref<const Vec3Array>& x,
                               const Eigen::Ref<const Vec3Array>& v, const Real gravity_magnitude,
                               const Real dt, Eigen::Ref<Vec3Array> force,
                               const DenseSprings* dense, Real* elastic_energy) {
  // Elastic energy as a by-product needs the dense springs; the other kinds are summed after.
  Real spring_energy = 0.0;
  Real* const by_product = dense && elastic_energy ? &spring_energy : nullptr;
  const auto index = [&particles](const ParticleId id) {
    return particles.denseIndexUnchecked(id);
  };

  for (const Drag& drag : generators.drags) {
    const std::size_t i = index(drag.particle);
    const Vec3 vi = v.col(i);
    // -(k1 |v| + k2 |v|^2) v/|v| = -(k1 + k2 |v|) v
    force.col(i) -= (drag.k1 + drag.k2 * vi.norm()) * vi;
  }

  if (dense) {
    accumulateDensePairForces(dense->springs, x, v, false, force, by_product);
  } else {
    accumulatePairForces(generators.springs, particles, x, v, false, force);
  }
  accumulateAnchoredForces(generators.anchored_springs, particles, x, v, false, force);
  if (dense) {
    accumulateDensePairForces(dense->bungees, x, v, true, force, by_product);
  } else {
    accumulatePairForces(generators.bungees, particles, x, v, true, force);
  }
  accumulateAnchoredForces(generators.anchored_bungees, particles, x, v, true, force);

  for (const Buoyancy& buoyancy : generators.buoyancies) {
    const std::size_t i = index(buoyancy.particle);
    const Real height = buoyancy.up.dot(x.col(i)) - buoyancy.surface_height;
    if (height >= buoyancy.max_depth) continue;
    const Real full = buoyancy.liquid_density * buoyancy.volume * gravity_magnitude;
    const Real submerged = height <= -buoyancy.max_depth
                               ? 1.0
                               : (buoyancy.max_depth - height) / (2.0 * buoyancy.max_depth);
    force.col(i) += full * submerged * buoyancy.up;
  }

  for (const StiffSpring& spring : generators.stiff_springs) {
    const std::size_t i = index(spring.particle);
    const Real inverse_mass = particles.inverseMasses()[i];
    if (inverse_mass <= 0.0 || dt <= 0.0) continue;
    const Vec3 x0 = x.col(i) - spring.anchor;
    const Vec3 v0 = v.col(i);
    const Vec3 target = dampedHarmonicPosition(x0, v0, spring.stiffness * inverse_mass,
                                               0.5 * spring.damping * inverse_mass, dt);
    // The constant acceleration that carries x0 to target in one step: x0 + v0 dt + a dt^2 = target
    const Vec3 acceleration = (target - x0 - v0 * dt) / (dt * dt);
    force.col(i) += acceleration / inverse_mass;
  }

  if (elastic_energy) {
    *elastic_energy = by_product ? spring_energy + nonPairPotentialEnergy(generators, particles, x)
                                 : generatorPotentialEnergy(generators, particles, dense);
  }
}

DenseSprings resolveDenseSprings(const ForceGenerators& generators,
                                 const ParticleStore& particles) {
  const auto resolve = [&particles](const auto& pairs, std::vector<DenseSpring>& out) {
    out.clear();
    out.reserve(pairs.size());
    for (const auto& pair : pairs) {
      out.push_back(DenseSpring{static_cast<std::uint32_t>(particles.denseIndexUnchecked(pair.a)),
                                static_cast<std::uint32_t>(particles.denseIndexUnchecked(pair.b)),
                                pair.stiffness, pair.rest_length, pair.damping});
    }
  };
  DenseSprings dense;
  resolve(generators.springs, dense.springs);
  resolve(generators.bungees, dense.bungees);
  return dense;
}

Real generatorPotentialEnergy(const ForceGenerators& generators, const ParticleStore& particles,
                              const DenseSprings* dense) {
  const auto x = particles.positions();
  const auto index = [&particles](const ParticleId id) {
    return particles.denseIndexUnchecked(id);
  };
  const auto elastic = [](const Real stiffness, const Real extension) {
    return 0.5 * stiffness * extension * extension;
  };
  Real energy = 0.0;
  const Real* const position = x.data();
  if (dense) {
    energy = addDensePairEnergy(energy, dense->springs, x, false);
  } else {
    for (const Spring& s : generators.springs) {
      const Real* const xa = position + 3 * index(s.a);
      const Real* const xb = position + 3 * index(s.b);
      const Real d[3] = {xa[0] - xb[0], xa[1] - xb[1], xa[2] - xb[2]};
      energy +=
          elastic(s.stiffness, std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) - s.rest_length);
    }
  }
  for (const AnchoredSpring& s : generators.anchored_springs) {
    energy += elastic(s.stiffness, (x.col(index(s.particle)) - s.anchor).norm() - s.rest_length);
  }
  if (dense) {
    energy = addDensePairEnergy(energy, dense->bungees, x, true);
  } else {
    for (const Bungee& s : generators.bungees) {
      const Real extension = (x.col(index(s.a)) - x.col(index(s.b))).norm() - s.rest_length;
      if (extension > 0.0) energy += elastic(s.stiffness, extension);
    }
  }
  for (const AnchoredBungee& s : generators.anchored_bungees) {
    const Real extension = (x.col(index(s.particle)) - s.anchor).norm() - s.rest_length;
    if (extension > 0.0) energy += elastic(s.stiffness, extension);
  }
  for (const StiffSpring& s : generators.stiff_springs) {
    energy += elastic(s.stiffness, (x.col(index(s.particle)) - s.anchor).norm());
  }
  return energy;
}

}  // namespace engine
}  // namespace mass_aggregate_sim
