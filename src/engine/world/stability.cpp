#include "mass_aggregate_sim/engine/world/stability.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <vector>

#include "engine/forces/body_force_stage.h"
#include "engine/forces/force_evaluation.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

constexpr Real kInfinity = std::numeric_limits<Real>::infinity();
constexpr int kMaxSubsteps = 1000;

constexpr std::size_t kAnchor = StiffnessTerm::kAnchorEnd;

// The fewest s with dt / s < h* (0: none up to kMaxSubsteps).
int fewestSubsteps(const Real dt, const Real largest_substep) {
  if (!(largest_substep > 0.0)) return 0;  // also NaN, from an omega that overflowed
  if (std::isinf(largest_substep)) return 1;
  const Real needed = std::floor(dt / largest_substep) + 1.0;
  return needed <= kMaxSubsteps ? static_cast<int>(needed) : 0;
}

// The spring a report names: its id, omega, the bound on the fastest mode it takes part in, that
// bound times h, and the integrator's limit there.
void nameSpring(StabilityReport& report, const GeneratorId id, const Real omega,
                const Real coupled_omega, const Real h, const Real limit) {
  report.generator = id;
  report.omega = omega;
  report.coupled_omega = coupled_omega;
  report.omega_h = coupled_omega * h;
  report.limit = limit;
}

// Completes a report whose worst term is set (generator, omega, coupled_omega, omega_h, limit)
// from its largest stable substep and the one that keeps the auto_substep margin. A spring's
// omega is its angular frequency; a drag's (`decay`) its rate.
void finishReport(StabilityReport& report, const char* what, const char* integrator, const Real dt,
                  const int substeps, const Real stable_substep, const Real margin_substep,
                  const bool decay = false) {
  const Real h = dt / static_cast<Real>(substeps);
  report.substeps_with_margin = fewestSubsteps(dt, margin_substep);
  report.stable = stable_substep > 0.0 && h / stable_substep < 1.0;
  report.stable_dt = stable_substep * static_cast<Real>(substeps);
  report.substeps_needed = fewestSubsteps(dt, stable_substep);
  if (report.stable) return;
  char measure[224];
  if (decay) {
    std::snprintf(measure, sizeof(measure), "rate*h = %.4g (rate = %.4g 1/s, h = %.4g s)",
                  report.omega_h, report.omega, h);
  } else {
    char with_damping[64] = "";
    if (report.damping_rate > 0.0) {
      std::snprintf(with_damping, sizeof(with_damping), ", damping c/mu %.4g 1/s",
                    report.damping_rate);
    }
    std::snprintf(measure, sizeof(measure),
                  "omega*h = %.4g (omega = %.4g rad/s, coupled %.4g rad/s%s, h = %.4g s)",
                  report.omega_h, report.omega, report.coupled_omega, with_damping, h);
  }
  char text[480];
  std::snprintf(text, sizeof(text),
                "%s %u is unstable with %s: %s exceeds the limit %.4g; stable for dt < %.4g s "
                "with %d substeps%s",
                what, static_cast<unsigned>(report.generator), integrator, measure, report.limit,
                report.stable_dt, substeps,
                report.substeps_needed > 0
                    ? (", or with " + std::to_string(report.substeps_needed) + " substeps").c_str()
                    : ", and no substep count up to 1000 makes it stable");
  report.message = text;
}

// The report on the fastest of `terms` (decays under `integrator` at substeps of dt / substeps).
StabilityReport decayReport(const std::vector<DecayTerm>& terms, const char* integrator_name,
                            const Real limit, const Real dt, const int substeps) {
  StabilityReport report;
  report.substeps_used = substeps;
  const DecayTerm* fastest = nullptr;
  for (const DecayTerm& t : terms) {
    if (t.rate > 0.0 && (!fastest || t.rate > fastest->rate)) fastest = &t;
  }
  if (!fastest) return report;
  const Real h = dt / static_cast<Real>(substeps);
  const Real rate = fastest->rate;
  nameSpring(report, fastest->id, rate, rate, h, limit);
  finishReport(report, fastest->angular ? "angular drag" : "drag", integrator_name, dt, substeps,
               limit / rate, kAutoSubstepMargin * limit / rate, true);
  return report;
}

}  // namespace

const char* divergencePolicyName(const DivergencePolicy policy) {
  switch (policy) {
    case DivergencePolicy::kContinue:
      return "continue";
    case DivergencePolicy::kPause:
      return "pause";
    case DivergencePolicy::kReset:
      return "reset";
  }
  return "unknown";
}

Real stabilityLimit(const Integrator integrator) {
  switch (integrator) {
    case Integrator::kExplicitEuler:
      return 0.0;
    case Integrator::kSemiImplicitEuler:
    case Integrator::kPositionVerlet:
    case Integrator::kVelocityVerlet:
      return 2.0;
    case Integrator::kRk4:
      return 2.0 * std::sqrt(2.0);
    case Integrator::kImplicitEuler:
      return kInfinity;
  }
  return 0.0;
}

Real stabilityLimit(const Integrator integrator, const Real damping, const Real h) {
  if (integrator != Integrator::kExplicitEuler) return stabilityLimit(integrator);
  if (damping >= 1.0 || h <= 0.0) return 0.0;
  // sqrt(d^-h - 1), with expm1 for accuracy when h ln d is small
  return std::sqrt(std::expm1(-h * std::log(damping)));
}

Real decayLimit(const Integrator integrator) {
  switch (integrator) {
    case Integrator::kExplicitEuler:
    case Integrator::kSemiImplicitEuler:
      return 2.0;
    case Integrator::kPositionVerlet:
    case Integrator::kVelocityVerlet:
      return 1.0;
    case Integrator::kRk4:
      return 2.785293563405282;  // the root of z^3 - 4 z^2 + 12 z - 24
    case Integrator::kImplicitEuler:
      return kInfinity;
  }
  return 0.0;
}

Real largestStableSubstep(const Integrator integrator, const Real omega, const Real damping,
                          const Real fraction) {
  if (omega <= 0.0) return kInfinity;
  if (integrator != Integrator::kExplicitEuler)
    return fraction * stabilityLimit(integrator) / omega;
  if (damping >= 1.0) return 0.0;
  if (damping <= 0.0) return kInfinity;
  // omega h - f sqrt(d^-h - 1) < 0 exactly on (0, h*): bisect for h*, starting from the small-h
  // estimate h* ~ -f^2 ln(d) / omega^2 and widening until the bracket holds.
  const auto stable = [&](const Real h) {
    return omega * h < fraction * stabilityLimit(integrator, damping, h);
  };
  Real low = 0.0;
  Real high = -fraction * fraction * std::log(damping) / (omega * omega);
  while (stable(high)) {
    low = high;
    high *= 2.0;
    if (high > 1e6) return kInfinity;
  }
  for (int i = 0; i < 100; ++i) {
    const Real mid = 0.5 * (low + high);
    (stable(mid) ? low : high) = mid;
  }
  return low;
}

Real largestStableDampedSubstep(const Integrator integrator, const Real omega, const Real gamma,
                                const Real damping, const Real fraction) {
  if (gamma <= 0.0 || integrator == Integrator::kExplicitEuler) {
    return largestStableSubstep(integrator, omega, damping, fraction);
  }
  switch (integrator) {
    case Integrator::kSemiImplicitEuler:
      // (omega h)^2 + 2 gamma h = 4; omega = 0: gamma h = 2
      return fraction * (omega > 0.0 ? (std::sqrt(gamma * gamma + 4.0 * omega * omega) - gamma) /
                                           (omega * omega)
                                     : decayLimit(integrator) / gamma);
    case Integrator::kPositionVerlet:
    case Integrator::kVelocityVerlet:
      // (omega h)^2 + 4 gamma h = 4; omega = 0: gamma h = 1
      return fraction * (omega > 0.0 ? 2.0 * (std::sqrt(gamma * gamma + omega * omega) - gamma) /
                                           (omega * omega)
                                     : decayLimit(integrator) / gamma);
    case Integrator::kRk4: {
      // The roots of lambda^2 + gamma lambda + omega^2 = 0, each inside RK4's region
      // |1 + z + z^2/2 + z^3/6 + z^4/24| <= 1 at z = h lambda: the largest h, by bisection.
      const std::complex<Real> root =
          std::sqrt(std::complex<Real>(0.25 * gamma * gamma - omega * omega, 0.0));
      const std::complex<Real> roots[2] = {-0.5 * gamma + root, -0.5 * gamma - root};
      const auto stable = [&](const Real h) {
        for (const std::complex<Real>& lambda : roots) {
          const std::complex<Real> z = h * lambda;
          const std::complex<Real> r = 1.0 + z * (1.0 + z * (0.5 + z * (1.0 / 6.0 + z / 24.0)));
          if (std::abs(r) > 1.0) return false;
        }
        return true;
      };
      Real low = 0.0;
      Real high = 4.0 / std::max(std::abs(roots[0]), std::abs(roots[1]));
      while (stable(high)) {
        low = high;
        high *= 2.0;
      }
      for (int i = 0; i < 100; ++i) {
        const Real mid = 0.5 * (low + high);
        (stable(mid) ? low : high) = mid;
      }
      return fraction * low;
    }
    case Integrator::kExplicitEuler:
    case Integrator::kImplicitEuler:
      break;
  }
  return kInfinity;
}

Real energySwing(const Integrator integrator, const Real omega_h) {
  // Explicit Euler has no bounded undamped orbit: every rise of its energy is growth.
  if (integrator == Integrator::kExplicitEuler) return 1.0;
  if (!(omega_h < stabilityLimit(integrator))) return kInfinity;
  const Real w2 = omega_h * omega_h;
  switch (integrator) {
    case Integrator::kSemiImplicitEuler:
      return (1.0 + 0.5 * omega_h) / (1.0 - 0.5 * omega_h);
    case Integrator::kVelocityVerlet:
      return 1.0 / (1.0 - 0.25 * w2);
    case Integrator::kPositionVerlet: {
      const Real b = 2.0 + 0.75 * w2;
      const Real r = 0.25 * w2 * std::sqrt(9.0 + 4.0 * w2);
      return (b + r) / (b - r);
    }
    case Integrator::kExplicitEuler:
    case Integrator::kRk4:
    case Integrator::kImplicitEuler:
      return 1.0;
  }
  return kInfinity;
}

Real guardSwing(const Integrator integrator, const Real omega_h) {
  return energySwing(integrator, std::min(omega_h, 0.999 * stabilityLimit(integrator)));
}

StabilityReport analyseStability(const ForceGenerators& generators, const ParticleStore& particles,
                                 const Integrator integrator, const Real dt, const int substeps,
                                 const bool with_damping) {
  StabilityReport report;
  report.substeps_used = substeps;
  report.limit = stabilityLimit(integrator);
  const std::size_t n = particles.size();
  const auto inverse_mass = particles.inverseMasses();
  const auto damping = particles.dampings();

  const std::vector<StiffnessTerm> terms = stiffnessTerms(generators, particles);

  // s_i = sum of sqrt(k) over the springs at particle i; d_i the same of sqrt(c)
  std::vector<Real> root_stiffness_sum(n, 0.0);
  std::vector<Real> root_damping_sum(n, 0.0);
  for (const StiffnessTerm& t : terms) {
    const Real root = std::sqrt(t.stiffness);
    const Real root_c = std::sqrt(t.damping);
    root_stiffness_sum[t.a] += root;
    root_damping_sum[t.a] += root_c;
    if (t.b != kAnchor) {
      root_stiffness_sum[t.b] += root;
      root_damping_sum[t.b] += root_c;
    }
  }

  const Real h = dt / static_cast<Real>(substeps);
  Real worst_ratio = -1.0;  // omega h relative to the limit, or h over the stable substep
  Real worst_stable_substep = kInfinity;
  Real worst_omega = 0.0;
  Real worst_gamma = 0.0;
  Real worst_damping = 1.0;
  for (const StiffnessTerm& t : terms) {
    if (t.stiffness <= 0.0) continue;
    const Real inverse_a = inverse_mass[t.a];
    const Real inverse_b = t.b == kAnchor ? 0.0 : inverse_mass[t.b];
    // 1/mu = 1/m_a + 1/m_b
    const Real inverse_mu = inverse_a + inverse_b;
    if (inverse_mu <= 0.0) continue;  // both ends immovable
    const Real omega = std::sqrt(t.stiffness * inverse_mu);
    Real coupled_square = root_stiffness_sum[t.a] * inverse_a;
    if (t.b != kAnchor) coupled_square += root_stiffness_sum[t.b] * inverse_b;
    const Real coupled_omega = std::sqrt(std::sqrt(t.stiffness) * coupled_square);
    // The spring's damping on the same line, bounded alike: gamma_e <= sqrt(c_e) (d_a / m_a +
    // d_b / m_b), c / mu for an isolated spring.
    Real coupled_damping = root_damping_sum[t.a] * inverse_a;
    if (t.b != kAnchor) coupled_damping += root_damping_sum[t.b] * inverse_b;
    const Real gamma = with_damping ? std::sqrt(t.damping) * coupled_damping : 0.0;
    // The weaker particle damping of the two movable ends governs explicit Euler.
    Real weakest_damping = inverse_a > 0.0 ? damping[t.a] : 0.0;
    if (t.b != kAnchor && inverse_b > 0.0)
      weakest_damping = std::max(weakest_damping, damping[t.b]);
    const Real stable_substep =
        largestStableDampedSubstep(integrator, coupled_omega, gamma, weakest_damping);
    const Real ratio = stable_substep > 0.0 ? h / stable_substep : kInfinity;
    if (ratio > worst_ratio) {
      worst_ratio = ratio;
      worst_stable_substep = stable_substep;
      const Real limit = gamma > 0.0 && integrator != Integrator::kExplicitEuler
                             ? coupled_omega * stable_substep
                             : stabilityLimit(integrator, weakest_damping, h);
      nameSpring(report, t.id, omega, coupled_omega, h, limit);
      report.damping_rate = gamma;
      worst_omega = coupled_omega;
      worst_gamma = gamma;
      worst_damping = weakest_damping;
    }
  }
  if (report.generator == 0) return report;
  finishReport(report, "spring", integratorName(integrator), dt, substeps, worst_stable_substep,
               largestStableDampedSubstep(integrator, worst_omega, worst_gamma, worst_damping,
                                          kAutoSubstepMargin));
  return report;
}

StabilityReport analysePointSpringStability(const BodyForceGenerators& generators,
                                            const BodyStore& bodies, const ParticleStore& particles,
                                            const Integrator particle_integrator, const Real dt,
                                            const int substeps) {
  StabilityReport report;
  report.substeps_used = substeps;
  std::vector<BodyStiffnessTerm> terms;
  const BodyForceScene scene(bodies, particles, nullptr, 0.0);
  generators.forEach([&](const auto& kind) {
    using Kind = typename std::decay_t<decltype(kind)>::value_type;
    BodyForceKind<Kind>::stiffness(kind, scene, terms);
  });
  const auto damping = particles.dampings();
  const Real h = dt / static_cast<Real>(substeps);
  Real worst_stable_substep = kInfinity;
  Real worst_margin_substep = kInfinity;
  bool worst_at_particle = false;
  for (const BodyStiffnessTerm& t : terms) {
    const Real mobility = t.mobility[0] + t.mobility[1];
    if (t.stiffness <= 0.0 || mobility <= 0.0) continue;  // no spring, or neither end moves
    const Real omega = std::sqrt(t.stiffness * mobility);
    const Real gamma = t.damping * mobility;
    Real stable_substep = kInfinity;
    Real margin_substep = kInfinity;
    Integrator binding = Integrator::kSemiImplicitEuler;
    Real binding_damping = 1.0;
    bool binding_particle = false;
    for (int e = 0; e < 2; ++e) {
      if (t.mobility[e] <= 0.0) continue;
      const bool particle = t.particle[e] >= 0;
      const Integrator integrator = particle ? particle_integrator : Integrator::kSemiImplicitEuler;
      const Real d = particle ? damping[static_cast<Eigen::Index>(t.particle[e])] : 1.0;
      const Real substep = largestStableDampedSubstep(integrator, omega, gamma, d);
      if (substep <= stable_substep) {
        stable_substep = substep;
        binding = integrator;
        binding_damping = d;
        binding_particle = particle;
      }
      margin_substep = std::min(margin_substep, largestStableDampedSubstep(integrator, omega, gamma,
                                                                           d, kAutoSubstepMargin));
    }
    if (report.generator != 0 && !(stable_substep < worst_stable_substep)) continue;
    worst_stable_substep = stable_substep;
    worst_margin_substep = margin_substep;
    const Real limit = gamma > 0.0 && binding != Integrator::kExplicitEuler
                           ? omega * stable_substep
                           : stabilityLimit(binding, binding_damping, h);
    nameSpring(report, t.id, omega, omega, h, limit);
    report.damping_rate = gamma;
    worst_at_particle = binding_particle;
  }
  if (report.generator == 0) return report;
  const std::string integrator =
      worst_at_particle ? std::string(integratorName(particle_integrator)) + " (its particle end)"
                        : std::string(integratorName(Integrator::kSemiImplicitEuler)) +
                              " (the bodies' integrator)";
  finishReport(report, "point spring", integrator.c_str(), dt, substeps, worst_stable_substep,
               worst_margin_substep);
  return report;
}

StabilityReport analyseDragStability(const ForceGenerators& generators,
                                     const ParticleStore& particles, const Integrator integrator,
                                     const Real dt, const int substeps) {
  std::vector<DecayTerm> terms;
  generators.forEach([&](const auto& kind) {
    using Kind = typename std::decay_t<decltype(kind)>::value_type;
    ForceKind<Kind>::decay(kind, particles, terms);
  });
  return decayReport(terms, integratorName(integrator), decayLimit(integrator), dt, substeps);
}

StabilityReport analyseBodyDragStability(const BodyForceGenerators& generators,
                                         const BodyStore& bodies, const ParticleStore& particles,
                                         const Real dt, const int substeps) {
  std::vector<DecayTerm> terms;
  const BodyForceScene scene(bodies, particles, nullptr, 0.0);
  generators.forEach([&](const auto& kind) {
    using Kind = typename std::decay_t<decltype(kind)>::value_type;
    BodyForceKind<Kind>::decay(kind, scene, terms);
  });
  const std::string integrator =
      std::string(integratorName(Integrator::kSemiImplicitEuler)) + " (the bodies' integrator)";
  return decayReport(terms, integrator.c_str(), decayLimit(Integrator::kSemiImplicitEuler), dt,
                     substeps);
}

StabilityReport bindingReport(const StabilityReport& a, const StabilityReport& b) {
  if (b.generator == 0) return a;
  if (a.generator == 0) return b;
  StabilityReport out = b.stable_dt < a.stable_dt ? b : a;
  out.stable = a.stable && b.stable;
  if (out.message.empty()) out.message = a.stable ? b.message : a.message;
  const auto most = [](const int x, const int y) { return x == 0 || y == 0 ? 0 : std::max(x, y); };
  out.substeps_needed = most(a.substeps_needed, b.substeps_needed);
  out.substeps_with_margin = most(a.substeps_with_margin, b.substeps_with_margin);
  return out;
}

}  // namespace engine
}  // namespace mass_aggregate_sim
