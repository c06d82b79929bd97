#include "engine/world/energy_guard.h"

#include <cmath>
#include <string>

#include "engine/world/energy_accumulator.h"
#include "engine/world/finite_check.h"
#include "engine/world/step_context.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

struct StepEnergies {
  Real free = 0.0;  // kinetic + elastic
  Real gravitational = 0.0;
  bool finite = true;
};

// The energies of the state the step ended in, with the finite probe: from the semi-implicit
// Euler pass's sums when it made them, else one pass over the particles. Where it can, the
// elastic energy comes from evaluating the next step's forces now (kept by the force stage for
// that step: the same calls on the same state, so the same bits).
StepEnergies energiesAfterStep(StepContext& ctx, const int substeps_used) {
  const ParticleStore& particles = ctx.particles;
  const Vec3& gravity = ctx.config.gravity;
  const Real g[3] = {gravity.x(), gravity.y(), gravity.z()};
  ParticleEnergies sums;
  if (ctx.caches.pass_energies_valid) {
    sums = ctx.caches.pass_energies;
  } else {
    EnergyAccumulator accumulator;
    accumulateParticleEnergies(particles.size(), ctx.caches.stability.mass.data(),
                               particles.positions().data(), particles.velocities().data(),
                               accumulator);
    sums = accumulator.sums(g);
  }
  StepEnergies energies;
  energies.gravitational = sums.gravitational;
  energies.finite = sums.finite();
  if (!energies.finite) return energies;
  // The next step must start from this state with one substep of the same h: no contact phase
  // (it would move particles after the forces).
  const bool ahead = ctx.config.integrator == Integrator::kSemiImplicitEuler &&
                     substeps_used == 1 && ctx.config.substeps == 1 && !ctx.contacts_active;
  const Real elastic = ahead ? ctx.caches.forces.evaluateAhead(ctx.scene, ctx.config.dt)
                             : ctx.caches.forces.elasticEnergy(ctx.scene);
  energies.free = 0.5 * sums.kinetic_twice + elastic;
  return energies;
}

}  // namespace

bool energyGuardApplies(const StepContext& ctx) {
  // Without generators every acceleration is constant: nothing can run away.
  return ctx.config.energy_growth_limit > 0.0 && !ctx.generators.empty() && !ctx.scene.external &&
         !ctx.caches.stability.uncounted_work;
}

namespace {

void reportFastest(StepContext& ctx) {
  const auto v = ctx.particles.velocities();
  std::size_t fastest = 0;
  Real most = 0.0;
  for (std::size_t i = 0; i < ctx.particles.size(); ++i) {
    const Real squared = v.col(i).squaredNorm();
    if (squared > most) {
      most = squared;
      fastest = i;
    }
  }
  if (!(most > ctx.collisions.runaway_speed * ctx.collisions.runaway_speed)) return;
  ctx.reportDivergence(ctx.particles.idAt(fastest),
                       "speed " + std::to_string(std::sqrt(most)) +
                           " m/s beyond the runaway speed after contacts and links acted");
}

}  // namespace

void detectNonFinite(StepContext& ctx, const bool runaway) {
  const auto x = ctx.particles.positions();
  const auto v = ctx.particles.velocities();
  const std::size_t count = 3 * ctx.particles.size();
  // |v|^2 <= 3 max_k v_k^2: with no component beyond limit / sqrt(3), no particle is beyond it.
  const Real limit = ctx.collisions.runaway_speed;
  bool beyond = false;
  bool finite;
  if (runaway) {
    finite = allFinite(x.data(), v.data(), count, limit * limit / 3.0, beyond);
  } else {
    finite = ctx.caches.pass_finite_valid ? ctx.caches.pass_finite
                                          : allFinite(x.data(), v.data(), count);
  }
  if (finite) {
    if (beyond) reportFastest(ctx);
    return;
  }
  for (std::size_t i = 0; i < ctx.particles.size(); ++i) {
    const bool bad_x = !x.col(i).allFinite();
    if (bad_x || !v.col(i).allFinite()) {
      ctx.reportDivergence(ctx.particles.idAt(i),
                           bad_x ? "position is not finite" : "velocity is not finite");
      return;
    }
  }
}

void detectBodyNonFinite(StepContext& ctx) {
  if (!ctx.bodies) return;
  const BodyStore& bodies = *ctx.bodies;
  const Real limit = ctx.body_settings->runaway_speed;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const Quat& q = bodies.orientation(i);
    const bool finite = bodies.position(i).allFinite() && q.coeffs().allFinite() &&
                        bodies.linearVelocity(i).allFinite() &&
                        bodies.angularVelocity(i).allFinite();
    if (!finite) {
      ctx.reportBodyDivergence(bodies.idAt(i), "body pose or velocity is not finite");
      return;
    }
    if (bodies.linearVelocity(i).norm() > limit) {
      ctx.reportBodyDivergence(bodies.idAt(i), "body speed " +
                                                   std::to_string(bodies.linearVelocity(i).norm()) +
                                                   " m/s beyond the runaway speed");
      return;
    }
  }
}

void judgeEnergy(StepContext& ctx, const StabilityReport& report, const int substeps_used) {
  GuardState& guard = ctx.guard;
  const StepEnergies energies = energiesAfterStep(ctx, substeps_used);
  if (!energies.finite) {
    // Not judged: a non-finite value is the divergence to report (and the energy meaningless).
    guard.energy_known = false;
    detectNonFinite(ctx);
    return;
  }
  const Real energy = energies.free + energies.gravitational;
  if (!guard.energy_known) {
    // The first step after a change gives the reference: by then every integrator reports its
    // velocity its own way (position Verlet's differs from the one it was seeded with).
    guard.free_energy = energies.free;
    guard.gravitational_energy = energies.gravitational;
    guard.energy = energy;
    guard.steps_since_reference = 0;
    guard.energy_known = true;
    return;
  }
  ++guard.steps_since_reference;
  const Real dt = ctx.config.dt;
  // Allowances: truncation of a constant force (explicit Euler gains m g^2 h^2 / 2 a substep),
  // and round-off in the sums.
  const Real truncation = ctx.caches.stability.movable_mass * ctx.config.gravity.squaredNorm() *
                          dt * dt * static_cast<Real>(guard.steps_since_reference);
  const Real round_off = 1e-9 * (std::abs(guard.gravitational_energy) +
                                 std::abs(energies.gravitational) + guard.free_energy);
  // Along a bounded orbit the integrator's reported energy swings by up to energySwing() of the
  // stiffest mode (the spring of the stability report); the limit is a margin on top of that.
  const Real omega_h = report.coupled_omega * dt / static_cast<Real>(substeps_used);
  const Real swing = guardSwing(ctx.config.integrator, omega_h);
  const Real growth = swing * (1.0 + ctx.config.energy_growth_limit) - 1.0;
  const Real bound = guard.energy + growth * guard.free_energy + truncation + round_off;
  if (energy <= bound) return;
  // Name the particle with the most kinetic energy: the runaway.
  const auto v = ctx.particles.velocities();
  const ScalarArray& mass = ctx.caches.stability.mass;
  std::size_t fastest = 0;
  Real most = -1.0;
  for (std::size_t i = 0; i < ctx.particles.size(); ++i) {
    const Real e = 0.5 * mass[i] * v.col(i).squaredNorm();
    if (e > most) {
      most = e;
      fastest = i;
    }
  }
  ctx.reportDivergence(ctx.particles.idAt(fastest),
                       "energy grew from " + std::to_string(guard.energy) + " J to " +
                           std::to_string(energy) + " J without external work (bound " +
                           std::to_string(bound) + " J)");
  guard.energy_known = false;
}

}  // namespace engine
}  // namespace mass_aggregate_sim
