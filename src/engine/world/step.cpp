// A step of the world: the context its stages share, built once, the stages of each substep in
// order, and what ends the step.
#include <algorithm>
#include <cmath>

#include "engine/bodies/body_stages.h"
#include "engine/bodies/body_workspace.h"
#include "engine/collision/contact_stages.h"
#include "engine/core/damping_flow.h"
#include "engine/forces/body_force_stage.h"
#include "engine/forces/force_evaluation.h"
#include "engine/integrators/integrators.h"
#include "engine/solver/contact_workspace.h"
#include "engine/solver/solver_stages.h"
#include "engine/world/energy_guard.h"
#include "engine/world/step_context.h"

namespace mass_aggregate_sim {
namespace engine {

void World::step() {
  if (paused_) return;
  StepContext ctx = beginStep();
  for (ctx.substep = 0; ctx.substep < ctx.substeps; ++ctx.substep) {
    applyForces(ctx);              // what the force stage needs from the start of the substep
    integrateVelocities(ctx);      // particles: the integrator (velocities, positions predicted)
    integrateBodyVelocities(ctx);  // bodies: forces and torques, the gyroscopic term implicit
    findPairs(ctx);                // candidate particle pairs; swept tests
    findBodyPairs(ctx);            // first substep: body contacts; bodies' surfaces for particles
    generateContacts(ctx);         // particles against colliders, body surfaces, each other; links
    generateBodyContacts(ctx);     // first substep: the step's body rows
    solveConstraints(ctx);         // particle rows: impulses, friction; resting particles follow
    solveBodyConstraints(ctx);     // body rows and joints: warm start, one soft pass
    integratePositions(ctx);       // particles: overlaps and link lengths corrected
    integrateBodyPositions(ctx);   // bodies follow their velocities; one pass to relax
  }
  finalise(ctx);  // restitution, bodies written back and put to sleep, time, the guards
}

namespace {

void refreshDampingFactors(const ParticleStore& particles, const Integrator integrator,
                           const Real h, DampingFactors& damping) {
  const std::size_t n = particles.size();
  const bool halves = integrator == Integrator::kPositionVerlet ||
                      integrator == Integrator::kVelocityVerlet || integrator == Integrator::kRk4;
  if (damping.h == h && damping.version == particles.dampingVersion() &&
      static_cast<std::size_t>(damping.decay.size()) == n && (damping.halves || !halves)) {
    return;
  }
  const auto d = particles.dampings();
  const auto size = static_cast<Eigen::Index>(n);
  damping.decay.resize(size);
  for (std::size_t i = 0; i < n; ++i) damping.decay[i] = dampingFlow(d[i], h).decay;
  if (halves) {
    damping.half_decay.resize(size);
    damping.half_gain.resize(size);
    for (std::size_t i = 0; i < n; ++i) {
      const DampingFlow half = dampingFlow(d[i], 0.5 * h);
      damping.half_decay[i] = half.decay;
      damping.half_gain[i] = half.gain;
    }
  }
  damping.h = h;
  damping.version = particles.dampingVersion();
  damping.halves = halves;
}

}  // namespace

StepContext World::beginStep() {
  const StabilityReport& report = stabilityReport();
  const bool reach = bodyForcesReachParticles(body_generators_);
  substeps_used_ = report.substeps_used;
  if (!bodies_.empty() && bodiesMove(reach)) {
    substeps_used_ = std::max(substeps_used_, body_settings_.substeps);
    body_substep_ = config_.dt / static_cast<Real>(substeps_used_);
  }
  StepCaches& caches = *caches_;
  StepContext ctx(
      config_, collision_settings_, particles_, generators_, links_, colliders_, materials_,
      ForceScene{particles_, generators_, generators_version_, config_.gravity,
                 has_external_force_ || reach},
      *integration_, caches, *contacts_, *guard_, last_contact_stats_, dropped_this_step_);
  ctx.dt = config_.dt;
  ctx.substeps = substeps_used_;
  ctx.h = config_.dt / static_cast<Real>(substeps_used_);
  ctx.step = step_count_;
  ctx.time = time();
  ctx.body_forces_reach_particles = reach;
  ctx.contacts_active = contactsActive();
  ctx.guard_energy = energyGuardApplies(ctx);
  // The guard and the divergence check read the state the step ends in: the semi-implicit Euler
  // pass sums or probes it unless contacts or stiff springs move particles afterwards.
  const bool pass_state_is_final = !ctx.contacts_active && generators_.of<StiffSpring>().empty();
  ctx.pass_sums_energies =
      ctx.guard_energy && pass_state_is_final &&
      caches.stability.mass.size() == static_cast<Eigen::Index>(particles_.size());
  ctx.pass_probes_finite = !ctx.guard_energy && pass_state_is_final;
  const auto n = static_cast<Eigen::Index>(particles_.size());
  if (integration_->acceleration.cols() != n) {
    integration_->acceleration.setZero(3, n);
    integration_->acceleration_valid = false;
  }
  refreshDampingFactors(particles_, config_.integrator, ctx.h, caches.damping);
  dropped_this_step_ = 0;
  caches.pass_energies_valid = false;
  caches.pass_finite_valid = false;
  if (!bodies_.empty()) {
    ctx.bodies = &bodies_;
    ctx.joints = &joints_;
    ctx.body_generators = &body_generators_;
    ctx.body_settings = &body_settings_;
    ctx.body_ws = &*body_ws_;
    ctx.colliders_version = colliders_version_;
    // Body contacts move particles after the integrator: the guard's sums come after them.
    ctx.pass_sums_energies = false;
    ctx.pass_probes_finite = false;
  }
  beginBodyStep(ctx);
  return ctx;
}

void World::finalise(StepContext& ctx) {
  const std::uint64_t divergences_before = guard_->divergence_count;
  finaliseBodies(ctx);
  if (has_external_force_ || ctx.scene.external) {
    // Held for the step only (the generators on bodies set theirs every substep). Velocity
    // Verlet's cached accelerations never hold them.
    particles_.forces().setZero();
    has_external_force_ = false;
    ctx.scene.external = false;
  }
  ++steps_since_origin_;
  ++step_count_;
  ctx.step = step_count_;
  ctx.time = time();
  // After the count, as for particles: an event names the step that produced it and its end time.
  detectBodyNonFinite(ctx);
  // Contact resolution and links remove energy but their position corrections may add a little:
  // a step with contacts takes a new reference instead of being judged.
  const bool had_contacts = ctx.contacts_active && last_contact_stats_.contacts > 0;
  if (ctx.guard_energy && !had_contacts) {
    judgeEnergy(ctx, caches_->stability.report, substeps_used_);
  } else {
    detectNonFinite(ctx, had_contacts);
    guard_->energy_known = false;
  }
  if (guard_->divergence_count != divergences_before) applyDivergencePolicy();
}

int World::advance(const Real frame_time) {
  const Real clamped = std::isfinite(frame_time)
                           ? std::clamp(frame_time, Real{0.0}, config_.max_frame_time)
                           : Real{0.0};
  accumulator_ += clamped;
  int steps = 0;
  while (accumulator_ >= config_.dt) {
    if (paused_) {
      accumulator_ = 0.0;
      break;
    }
    step();
    accumulator_ -= config_.dt;
    ++steps;
  }
  return steps;
}

bool World::contactsActive() const {
  return !colliders_.empty() || !links_.empty() ||
         (collision_settings_.particle_collisions && particles_.size() > 1);
}

const StabilityReport& World::stabilityReport() const {
  StabilityCache& cache = caches_->stability;
  // Particle add and remove also bump the damping version; masses only change through them.
  const StabilityCache::Inputs inputs{
      particles_.size(), generators_.size(), generators_version_, particles_.dampingVersion(),
      config_.dt,        config_.substeps,   config_.integrator};
  if (!cache.valid || !(inputs == cache.inputs)) {
    cache.inputs = inputs;
    cache.report = analyseStability(generators_, particles_, config_.integrator, config_.dt,
                                    config_.substeps, false);
    cache.damped =
        analyseStability(generators_, particles_, config_.integrator, config_.dt, config_.substeps);
    cache.drag = analyseDragStability(generators_, particles_, config_.integrator, config_.dt,
                                      config_.substeps);
    const auto own_acceleration = particles_.accelerations();
    const auto inverse_mass = particles_.inverseMasses();
    cache.movable_mass = 0.0;
    cache.mass.setZero(static_cast<Eigen::Index>(particles_.size()));
    bool own = false;
    for (std::size_t i = 0; i < particles_.size(); ++i) {
      if (inverse_mass[i] <= 0.0) continue;
      cache.mass[i] = 1.0 / inverse_mass[i];
      cache.movable_mass += cache.mass[i];
      own = own || !own_acceleration.col(i).isZero(0.0);
    }
    cache.uncounted_work = own || generatorsDoUncountedWork(generators_);
    cache.valid = true;
  }
  // The damped springs' report binds at least as tightly as the undamped one the guard reads.
  StabilityReport* binding = &cache.damped;
  if (!body_generators_.empty() || cache.drag.generator != 0) {
    cache.with_bodies = bindingReport(cache.damped, cache.drag);
    if (!body_generators_.empty()) {
      const int body_substeps = std::max(config_.substeps, body_settings_.substeps);
      cache.with_bodies = bindingReport(
          bindingReport(cache.with_bodies,
                        analysePointSpringStability(body_generators_, bodies_, particles_,
                                                    config_.integrator, config_.dt, body_substeps)),
          analyseBodyDragStability(body_generators_, bodies_, particles_, config_.dt,
                                   body_substeps));
    }
    binding = &cache.with_bodies;
  }
  // `stable` stays about config().substeps (the warning); substeps_used is what step() takes.
  // auto_substep keeps the kAutoSubstepMargin when 1000 substeps can, else just stability.
  StabilityReport& report = *binding;
  const int wanted =
      report.substeps_with_margin > 0 ? report.substeps_with_margin : report.substeps_needed;
  const bool raise = config_.auto_substep && wanted > config_.substeps;
  report.substeps_used = raise ? wanted : config_.substeps;
  return report;
}

const std::optional<DivergenceEvent>& World::lastDivergence() const {
  return guard_->last_divergence;
}

std::uint64_t World::divergenceCount() const { return guard_->divergence_count; }

void World::applyDivergencePolicy() {
  switch (config_.divergence_policy) {
    case DivergencePolicy::kContinue:
      return;
    case DivergencePolicy::kPause:
      paused_ = true;
      return;
    case DivergencePolicy::kReset:
      if (!reset_snapshot_) {
        paused_ = true;
        return;
      }
      // Everything comes back but the record of what happened and the snapshot itself.
      const GuardState record = *guard_;
      const std::shared_ptr<const World> snapshot = reset_snapshot_;
      *this = *snapshot;
      guard_->last_divergence = record.last_divergence;
      guard_->divergence_count = record.divergence_count;
      reset_snapshot_ = snapshot;
      paused_ = false;
      return;
  }
}

void World::setResetSnapshot() {
  auto snapshot = std::make_shared<World>(*this);
  snapshot->reset_snapshot_.reset();  // no chain of older snapshots
  snapshot->paused_ = false;
  reset_snapshot_ = std::move(snapshot);
}

}  // namespace engine
}  // namespace mass_aggregate_sim
