// The stiff spring kind (stiff_spring.h): a particle held by stiff springs moves over each
// substep as the exact damped harmonic motion about its equilibrium, with everything else acting
// on it held at its value at the start of the substep. That is exact for position and velocity at
// any stiffness and under every integrator, for a particle the rest of the scene pushes with a
// constant force (gravity, a steady pull); the integrators still see the spring as a constant
// acceleration (below), so what the particle's neighbours feel during the substep follows it.
#include "mass_aggregate_sim/engine/forces/stiff_spring.h"

#include <algorithm>
#include <cmath>

#include "engine/core/checks.h"
#include "engine/forces/damped_harmonic.h"
#include "engine/forces/force_evaluation.h"
#include "engine/forces/stiff_spring_stage.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

// The constant acceleration that carries the particle from (x, v) to where the spring's exact
// damped motion puts it after dt: x0 + v0 dt + a dt^2 = target.
Vec3 equivalentAcceleration(const StiffSpring& spring, const Vec3& x, const Vec3& v,
                            const Real inverse_mass, const Real dt) {
  const Vec3 x0 = x - spring.anchor;
  const Vec3 target = dampedHarmonicMotion(x0, v, spring.stiffness * inverse_mass,
                                           0.5 * spring.damping * inverse_mass, dt)
                          .position;
  return (target - x0 - v * dt) / (dt * dt);
}

bool byIndex(const StiffParticle& a, const StiffParticle& b) { return a.index < b.index; }

}  // namespace

DrawnSegment ForceKind<StiffSpring>::drawn(const StiffSpring& spring,
                                           const ParticleStore& particles) {
  const Vec3 a = particles.positions().col(particles.denseIndexUnchecked(spring.particle));
  return DrawnSegment{a, spring.anchor, spring.stiffness * (a - spring.anchor).norm()};
}

Status ForceKind<StiffSpring>::validate(StiffSpring& spring, const ParticleStore& particles) {
  const Status particle = particles.checkReference(spring.particle, "particle");
  if (!particle) return particle;
  if (!spring.anchor.allFinite()) return Status::error("anchor is not finite");
  if (!finiteNonNegative(spring.stiffness)) {
    return Status::error("stiffness must be finite and >= 0");
  }
  if (!finiteNonNegative(spring.damping)) return Status::error("damping must be finite and >= 0");
  return Status::ok();
}

void ForceKind<StiffSpring>::accumulate(const std::vector<StiffSpring>& springs,
                                        const ForceEvaluation& e, Eigen::Ref<Vec3Array> force,
                                        Real* elastic) {
  const auto inverse_mass = e.particles.inverseMasses();
  for (const StiffSpring& spring : springs) {
    const std::size_t i = e.particles.denseIndexUnchecked(spring.particle);
    if (elastic) {
      const Real extension = (e.x.col(i) - spring.anchor).norm();
      *elastic += 0.5 * spring.stiffness * extension * extension;
    }
    if (inverse_mass[i] <= 0.0 || e.dt <= 0.0) continue;
    force.col(i) += equivalentAcceleration(spring, e.x.col(i), e.v.col(i), inverse_mass[i], e.dt) /
                    inverse_mass[i];
  }
}

Real ForceKind<StiffSpring>::energy(const std::vector<StiffSpring>& springs,
                                    const ForceEvaluation& e) {
  Real energy = 0.0;
  for (const StiffSpring& s : springs) {
    const Real extension = (e.x.col(e.particles.denseIndexUnchecked(s.particle)) - s.anchor).norm();
    energy += 0.5 * s.stiffness * extension * extension;
  }
  return energy;
}

void prepareStiffSprings(const std::vector<StiffSpring>& springs, const ParticleStore& particles,
                         const Eigen::Ref<const Vec3Array>& acceleration, const Real h,
                         std::vector<StiffParticle>& out) {
  out.clear();
  const auto x = particles.positions();
  const auto v = particles.velocities();
  const auto inverse_mass = particles.inverseMasses();
  for (const StiffSpring& spring : springs) {
    const std::size_t i = particles.denseIndexUnchecked(spring.particle);
    if (inverse_mass[i] <= 0.0) continue;
    StiffParticle particle;
    particle.index = i;
    particle.position = x.col(i);
    particle.velocity = v.col(i);
    particle.other_acceleration = acceleration.col(i);
    out.push_back(particle);
  }
  std::sort(out.begin(), out.end(), byIndex);
  out.erase(std::unique(
                out.begin(), out.end(),
                [](const StiffParticle& a, const StiffParticle& b) { return a.index == b.index; }),
            out.end());
  // Everything else on the particle: the whole acceleration less the springs' own share.
  for (const StiffSpring& spring : springs) {
    StiffParticle key;
    key.index = particles.denseIndexUnchecked(spring.particle);
    const auto it = std::lower_bound(out.begin(), out.end(), key, byIndex);
    if (it == out.end() || it->index != key.index) continue;  // immovable
    const std::size_t i = key.index;
    it->other_acceleration -=
        equivalentAcceleration(spring, x.col(i), v.col(i), inverse_mass[i], h);
    it->stiffness += spring.stiffness;
    it->weighted_anchor += spring.stiffness * spring.anchor;
    it->damping += spring.damping;
  }
}

void applyStiffSprings(const std::vector<StiffParticle>& held, ParticleStore& particles,
                       const Real h) {
  auto x = particles.positions();
  auto v = particles.velocities();
  auto seeded = particles.historySeeded();
  const auto inverse_mass = particles.inverseMasses();
  const auto damping = particles.dampings();
  for (const StiffParticle& particle : held) {
    if (particle.stiffness <= 0.0) continue;  // springs of stiffness 0 do nothing
    const std::size_t i = particle.index;
    seeded[i] = 0.0;
    if (damping[i] <= 0.0) {
      // d = 0 keeps no velocity: the particle stays where it was.
      x.col(i) = particle.position;
      v.col(i).setZero();
      continue;
    }
    // m x'' = -k (x - anchor) - c x' + m ln(d) x' + m a_other: with w2 = k / m and
    // 2 beta = c / m - ln d, the damped harmonic motion about centre = anchor + a_other / w2.
    const Real w2 = particle.stiffness * inverse_mass[i];
    const Real beta = 0.5 * (particle.damping * inverse_mass[i] - std::log(damping[i]));
    const Vec3 centre =
        particle.weighted_anchor / particle.stiffness + particle.other_acceleration / w2;
    const HarmonicState motion =
        dampedHarmonicMotion(particle.position - centre, particle.velocity, w2, beta, h);
    x.col(i) = centre + motion.position;
    v.col(i) = motion.velocity;
  }
}

}  // namespace engine
}  // namespace mass_aggregate_sim
