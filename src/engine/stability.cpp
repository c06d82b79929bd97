#include "mass_aggregate_sim/engine/stability.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

namespace mass_aggregate_sim {
namespace engine {
namespace {

constexpr Real kInfinity = std::numeric_limits<Real>::infinity();
constexpr int kMaxSubsteps = 1000;

// One spring's data for the analysis: its ends (dense; npos for an anchor) and stiffness.
struct SpringTerm {
  GeneratorId id;
  std::size_t a;
  std::size_t b;
  Real stiffness;
};
constexpr std::size_t kAnchor = static_cast<std::size_t>(-1);

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

Real largestStableSubstep(const Integrator integrator, const Real omega, const Real damping) {
  if (omega <= 0.0) return kInfinity;
  if (integrator != Integrator::kExplicitEuler) return stabilityLimit(integrator) / omega;
  if (damping >= 1.0) return 0.0;
  if (damping <= 0.0) return kInfinity;
  // omega h - sqrt(d^-h - 1) < 0 exactly on (0, h*): bisect for h*, starting from the small-h
  // estimate h* ~ -ln(d) / omega^2 and widening until the bracket holds.
  const auto stable = [&](const Real h) {
    return omega * h < stabilityLimit(integrator, damping, h);
  };
  Real low = 0.0;
  Real high = -std::log(damping) / (omega * omega);
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

StabilityReport analyseStability(const ForceGenerators& generators, const ParticleStore& particles,
                                 const Integrator integrator, const Real dt, const int substeps) {
  StabilityReport report;
  report.substeps_used = substeps;
  report.limit = stabilityLimit(integrator);
  const std::size_t n = particles.size();
  const auto inverse_mass = particles.inverseMasses();
  const auto damping = particles.dampings();

  std::vector<SpringTerm> terms;
  terms.reserve(generators.springs.size() + generators.bungees.size() +
                generators.anchored_springs.size() + generators.anchored_bungees.size());
  const auto index = [&particles](const ParticleId id) {
    return particles.denseIndexUnchecked(id);
  };
  for (const Spring& s : generators.springs) {
    terms.push_back({s.id, index(s.a), index(s.b), s.stiffness});
  }
  for (const Bungee& s : generators.bungees) {
    terms.push_back({s.id, index(s.a), index(s.b), s.stiffness});
  }
  for (const AnchoredSpring& s : generators.anchored_springs) {
    terms.push_back({s.id, index(s.particle), kAnchor, s.stiffness});
  }
  for (const AnchoredBungee& s : generators.anchored_bungees) {
    terms.push_back({s.id, index(s.particle), kAnchor, s.stiffness});
  }

  // s_i = sum of sqrt(k) over the springs at particle i
  std::vector<Real> root_stiffness_sum(n, 0.0);
  for (const SpringTerm& t : terms) {
    const Real root = std::sqrt(t.stiffness);
    root_stiffness_sum[t.a] += root;
    if (t.b != kAnchor) root_stiffness_sum[t.b] += root;
  }

  const Real h = dt / static_cast<Real>(substeps);
  Real worst_ratio = -1.0;  // omega h relative to the limit, or h over the stable substep
  Real worst_stable_substep = kInfinity;
  for (const SpringTerm& t : terms) {
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
    // The weaker particle damping of the two movable ends governs explicit Euler.
    Real weakest_damping = inverse_a > 0.0 ? damping[t.a] : 0.0;
    if (t.b != kAnchor && inverse_b > 0.0)
      weakest_damping = std::max(weakest_damping, damping[t.b]);
    const Real stable_substep = largestStableSubstep(integrator, coupled_omega, weakest_damping);
    const Real ratio = stable_substep > 0.0 ? h / stable_substep : kInfinity;
    if (ratio > worst_ratio) {
      worst_ratio = ratio;
      worst_stable_substep = stable_substep;
      report.generator = t.id;
      report.omega = omega;
      report.coupled_omega = coupled_omega;
      report.omega_h = coupled_omega * h;
      report.limit = stabilityLimit(integrator, weakest_damping, h);
    }
  }
  if (report.generator == 0) return report;

  report.stable = worst_ratio < 1.0;
  report.stable_dt = worst_stable_substep * static_cast<Real>(substeps);
  if (!(worst_stable_substep > 0.0)) {  // also NaN, from an omega that overflowed
    report.substeps_needed = 0;
  } else if (std::isinf(worst_stable_substep)) {
    report.substeps_needed = 1;
  } else {
    // the fewest s with dt / s < h*
    const Real needed = std::floor(dt / worst_stable_substep) + 1.0;
    report.substeps_needed = needed <= kMaxSubsteps ? static_cast<int>(needed) : 0;
  }
  if (!report.stable) {
    char text[320];
    std::snprintf(
        text, sizeof(text),
        "spring %u is unstable with %s: omega*h = %.4g (omega = %.4g rad/s, coupled "
        "%.4g rad/s, h = %.4g s) exceeds the limit %.4g; stable for dt < %.4g s with "
        "%d substeps%s",
        static_cast<unsigned>(report.generator), integratorName(integrator), report.omega_h,
        report.omega, report.coupled_omega, h, report.limit, report.stable_dt, substeps,
        report.substeps_needed > 0
            ? (", or with " + std::to_string(report.substeps_needed) + " substeps").c_str()
            : ", and no substep count up to 1000 makes it stable");
    report.message = text;
  }
  return report;
}

}  // namespace engine
}  // namespace mass_aggregate_sim
