#include "mass_aggregate_sim/engine/force_evaluation.h"

#include <cmath>

namespace mass_aggregate_sim {
namespace engine {
namespace {

constexpr Real kMinLength = 1e-12;

// Force on the first end of a spring from a to b (the second end gets the opposite).
// With d = x_a - x_b, l = |d|, n = d / l: F_a = -(k (l - L) + c (v_a - v_b).n) n.
// `pull_only` makes it a bungee: nothing while l <= L.
inline Vec3 springForce(const Vec3& d, const Vec3& relative_velocity, const Real stiffness,
                        const Real rest_length, const Real damping, const bool pull_only) {
  const Real length = d.norm();
  if (length < kMinLength) return Vec3::Zero();
  const Real extension = length - rest_length;
  if (pull_only && extension <= 0.0) return Vec3::Zero();
  const Vec3 n = d / length;
  return -(stiffness * extension + damping * relative_velocity.dot(n)) * n;
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

}  // namespace

void accumulateGeneratorForces(const ForceGenerators& generators, const ParticleStore& particles,
                               const Eigen::Ref<const Vec3Array>& x,
                               const Eigen::Ref<const Vec3Array>& v, const Real gravity_magnitude,
                               const Real dt, Eigen::Ref<Vec3Array> force) {
  const auto index = [&particles](const ParticleId id) {
    return particles.denseIndexUnchecked(id);
  };

  for (const Drag& drag : generators.drags) {
    const std::size_t i = index(drag.particle);
    const Vec3 vi = v.col(i);
    // -(k1 |v| + k2 |v|^2) v/|v| = -(k1 + k2 |v|) v
    force.col(i) -= (drag.k1 + drag.k2 * vi.norm()) * vi;
  }

  for (const Spring& spring : generators.springs) {
    const std::size_t a = index(spring.a);
    const std::size_t b = index(spring.b);
    const Vec3 f = springForce(x.col(a) - x.col(b), v.col(a) - v.col(b), spring.stiffness,
                               spring.rest_length, spring.damping, false);
    force.col(a) += f;
    force.col(b) -= f;
  }

  for (const AnchoredSpring& spring : generators.anchored_springs) {
    const std::size_t i = index(spring.particle);
    force.col(i) += springForce(x.col(i) - spring.anchor, v.col(i), spring.stiffness,
                                spring.rest_length, spring.damping, false);
  }

  for (const Bungee& bungee : generators.bungees) {
    const std::size_t a = index(bungee.a);
    const std::size_t b = index(bungee.b);
    const Vec3 f = springForce(x.col(a) - x.col(b), v.col(a) - v.col(b), bungee.stiffness,
                               bungee.rest_length, bungee.damping, true);
    force.col(a) += f;
    force.col(b) -= f;
  }

  for (const AnchoredBungee& bungee : generators.anchored_bungees) {
    const std::size_t i = index(bungee.particle);
    force.col(i) += springForce(x.col(i) - bungee.anchor, v.col(i), bungee.stiffness,
                                bungee.rest_length, bungee.damping, true);
  }

  for (const Buoyancy& buoyancy : generators.buoyancies) {
    const std::size_t i = index(buoyancy.particle);
    const Real height = buoyancy.up.dot(x.col(i)) - buoyancy.surface_height;
    if (height >= buoyancy.max_depth) continue;
    const Real full = buoyancy.liquid_density * buoyancy.volume * gravity_magnitude;
    const Real submerged =
        height <= -buoyancy.max_depth ? 1.0 : (buoyancy.max_depth - height) / (2.0 * buoyancy.max_depth);
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
}

Real generatorPotentialEnergy(const ForceGenerators& generators, const ParticleStore& particles) {
  const auto x = particles.positions();
  const auto index = [&particles](const ParticleId id) {
    return particles.denseIndexUnchecked(id);
  };
  const auto elastic = [](const Real stiffness, const Real extension) {
    return 0.5 * stiffness * extension * extension;
  };
  Real energy = 0.0;
  for (const Spring& s : generators.springs) {
    energy += elastic(s.stiffness, (x.col(index(s.a)) - x.col(index(s.b))).norm() - s.rest_length);
  }
  for (const AnchoredSpring& s : generators.anchored_springs) {
    energy += elastic(s.stiffness, (x.col(index(s.particle)) - s.anchor).norm() - s.rest_length);
  }
  for (const Bungee& s : generators.bungees) {
    const Real extension = (x.col(index(s.a)) - x.col(index(s.b))).norm() - s.rest_length;
    if (extension > 0.0) energy += elastic(s.stiffness, extension);
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
