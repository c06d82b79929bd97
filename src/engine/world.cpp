#include "mass_aggregate_sim/engine/world.h"

#include <algorithm>
#include <cmath>
#include <tuple>

#include "mass_aggregate_sim/engine/contact_workspace.h"
#include "mass_aggregate_sim/engine/energy_accumulator.h"
#include "mass_aggregate_sim/engine/finite_check.h"
#include "mass_aggregate_sim/engine/force_evaluation.h"
#include "mass_aggregate_sim/engine/implicit_euler.h"
#include "mass_aggregate_sim/engine/state_hash.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

bool finiteNonNegative(const Real value) { return std::isfinite(value) && value >= 0.0; }

Status checkSpringValues(const Real stiffness, const Real rest_length, const Real damping) {
  if (!finiteNonNegative(stiffness)) return Status::error("stiffness must be finite and >= 0");
  if (!finiteNonNegative(rest_length)) return Status::error("rest_length must be finite and >= 0");
  if (!finiteNonNegative(damping)) return Status::error("damping must be finite and >= 0");
  return Status::ok();
}

template <typename Generator>
bool refersTo(const Generator& g, const ParticleId id) {
  if constexpr (std::is_same_v<Generator, Spring> || std::is_same_v<Generator, Bungee> ||
                std::is_same_v<Generator, Cable> || std::is_same_v<Generator, Rod>) {
    return g.a == id || g.b == id;
  } else {
    return g.particle == id;
  }
}

template <typename Generator>
void eraseReferencing(std::vector<Generator>& kind, const ParticleId id) {
  kind.erase(std::remove_if(kind.begin(), kind.end(),
                            [id](const Generator& g) { return refersTo(g, id); }),
             kind.end());
}

template <typename Generator>
bool eraseById(std::vector<Generator>& kind, const GeneratorId id) {
  const auto it =
      std::find_if(kind.begin(), kind.end(), [id](const Generator& g) { return g.id == id; });
  if (it == kind.end()) return false;
  kind.erase(it);
  return true;
}

}  // namespace

World::World(const WorldConfig& config)
    : implicit_solver_(std::make_unique<ImplicitEulerSolver>()) {
  const Status valid = setConfig(config);
  if (!valid) config_ = WorldConfig{};
}

World::~World() = default;
World::World(World&&) noexcept = default;
World& World::operator=(World&&) noexcept = default;

World::World(const World& other)
    : config_(other.config_),
      particles_(other.particles_),
      generators_(other.generators_),
      next_generator_id_(other.next_generator_id_),
      time_origin_(other.time_origin_),
      steps_since_origin_(other.steps_since_origin_),
      step_count_(other.step_count_),
      accumulator_(other.accumulator_),
      has_external_force_(other.has_external_force_),
      damping_factor_(other.damping_factor_),
      damping_factor_h_(other.damping_factor_h_),
      damping_factor_version_(other.damping_factor_version_),
      verlet_history_h_(other.verlet_history_h_),
      acceleration_valid_(other.acceleration_valid_),
      acceleration_(other.acceleration_),
      implicit_solver_(std::make_unique<ImplicitEulerSolver>()),
      last_divergence_(other.last_divergence_),
      divergence_count_(other.divergence_count_),
      stability_report_(other.stability_report_),
      stability_dirty_(other.stability_dirty_),
      stability_inputs_(other.stability_inputs_),
      has_uncounted_work_(other.has_uncounted_work_),
      movable_mass_(other.movable_mass_),
      mass_(other.mass_),
      substeps_used_(other.substeps_used_),
      energy_known_(other.energy_known_),
      energy_(other.energy_),
      free_energy_(other.free_energy_),
      gravitational_energy_(other.gravitational_energy_),
      steps_since_energy_reference_(other.steps_since_energy_reference_),
      paused_(other.paused_),
      reset_snapshot_(other.reset_snapshot_),
      colliders_(other.colliders_),
      next_collider_id_(other.next_collider_id_),
      links_(other.links_),
      collision_settings_(other.collision_settings_),
      last_contact_stats_(other.last_contact_stats_),
      dropped_this_step_(other.dropped_this_step_),
      slot_material_(other.slot_material_),
      slot_has_material_(other.slot_has_material_),
      custom_material_count_(other.custom_material_count_),
      contact_workspace_(other.contact_workspace_
                             ? std::make_unique<ContactWorkspace>(*other.contact_workspace_)
                             : nullptr) {}

World& World::operator=(const World& other) {
  if (this != &other) *this = World(other);
  return *this;
}

Status World::setConfig(const WorldConfig& config) {
  const Status valid = validateConfig(config);
  if (!valid) return valid;
  if (config.dt != config_.dt) {
    // Keep time exact: restart counting steps of the new dt from the current time.
    time_origin_ = time();
    steps_since_origin_ = 0;
    accumulator_ = 0.0;
  }
  config_ = config;
  invalidateCaches();
  return Status::ok();
}

Status World::validateParticleRef(const ParticleId id, const char* field) const {
  if (particles_.contains(id)) return Status::ok();
  return Status::error(std::string(field) + ": " + particles_.describeInvalid(id));
}

Result<ParticleId> World::addParticle(const ParticleSpec& spec) {
  const Status valid = validateSpec(spec);
  if (!valid) return valid;
  const ParticleId id = particles_.add(spec);
  invalidateCaches();
  return id;
}

Status World::removeParticle(const ParticleId id) {
  const Status valid = validateParticleRef(id, "particle");
  if (!valid) return valid;
  eraseReferencing(generators_.drags, id);
  eraseReferencing(generators_.springs, id);
  eraseReferencing(generators_.anchored_springs, id);
  eraseReferencing(generators_.bungees, id);
  eraseReferencing(generators_.anchored_bungees, id);
  eraseReferencing(generators_.buoyancies, id);
  eraseReferencing(generators_.stiff_springs, id);
  eraseReferencing(links_.cables, id);
  eraseReferencing(links_.rods, id);
  eraseReferencing(links_.anchored_cables, id);
  eraseReferencing(links_.anchored_rods, id);
  if (id.index < slot_has_material_.size() && slot_has_material_[id.index]) {
    slot_has_material_[id.index] = 0;
    --custom_material_count_;
  }
  const Status removed = particles_.remove(id);
  if (contact_workspace_) contact_workspace_->resolver.clearWarmStart();
  invalidateCaches();
  return removed;
}

Status World::setPosition(const ParticleId id, const Vec3& position) {
  const auto dense = particles_.find(id);
  if (!dense) return Status::error("particle: " + particles_.describeInvalid(id));
  if (!position.allFinite()) return Status::error("position is not finite");
  particles_.positions().col(*dense) = position;
  invalidateCaches();
  return Status::ok();
}

Status World::setVelocity(const ParticleId id, const Vec3& velocity) {
  const auto dense = particles_.find(id);
  if (!dense) return Status::error("particle: " + particles_.describeInvalid(id));
  if (!velocity.allFinite()) return Status::error("velocity is not finite");
  if (particles_.inverseMasses()[*dense] <= 0.0 && !velocity.isZero(0.0)) {
    return Status::error("particle " + id.str() + " is immovable: its velocity stays zero");
  }
  particles_.velocities().col(*dense) = velocity;
  invalidateCaches();
  return Status::ok();
}

Status World::applyImpulse(const ParticleId id, const Vec3& impulse) {
  const auto dense = particles_.find(id);
  if (!dense) return Status::error("particle: " + particles_.describeInvalid(id));
  if (!impulse.allFinite()) return Status::error("impulse is not finite");
  const Real inverse_mass = particles_.inverseMasses()[*dense];
  if (inverse_mass <= 0.0) {
    return Status::error("particle " + id.str() + " is immovable: an impulse cannot move it");
  }
  // dv = J / m
  particles_.velocities().col(*dense) += impulse * inverse_mass;
  invalidateCaches();
  return Status::ok();
}

Status World::addForce(const ParticleId id, const Vec3& force) {
  const auto dense = particles_.find(id);
  if (!dense) return Status::error("particle: " + particles_.describeInvalid(id));
  if (!force.allFinite()) return Status::error("force is not finite");
  particles_.forces().col(*dense) += force;
  has_external_force_ = true;
  invalidateCaches();
  return Status::ok();
}

template <typename Generator>
Result<GeneratorId> World::addGenerator(std::vector<Generator>& kind, Generator generator) {
  generator.id = next_generator_id_++;
  kind.push_back(generator);
  invalidateCaches();
  return generator.id;
}

// Links share the generators' id space (added in world_contacts.cpp).
template Result<GeneratorId> World::addGenerator(std::vector<Cable>&, Cable);
template Result<GeneratorId> World::addGenerator(std::vector<Rod>&, Rod);
template Result<GeneratorId> World::addGenerator(std::vector<AnchoredCable>&, AnchoredCable);
template Result<GeneratorId> World::addGenerator(std::vector<AnchoredRod>&, AnchoredRod);

Result<GeneratorId> World::addDrag(const Drag& drag) {
  Status valid = validateParticleRef(drag.particle, "particle");
  if (valid && (!finiteNonNegative(drag.k1) || !finiteNonNegative(drag.k2))) {
    valid = Status::error("drag coefficients k1 and k2 must be finite and >= 0");
  }
  if (!valid) return valid;
  return addGenerator(generators_.drags, drag);
}

Result<GeneratorId> World::addSpring(const Spring& spring) {
  Status valid = validateParticleRef(spring.a, "a");
  if (valid) valid = validateParticleRef(spring.b, "b");
  if (valid && spring.a == spring.b) valid = Status::error("a and b must be different particles");
  if (valid) valid = checkSpringValues(spring.stiffness, spring.rest_length, spring.damping);
  if (!valid) return valid;
  return addGenerator(generators_.springs, spring);
}

Result<GeneratorId> World::addAnchoredSpring(const AnchoredSpring& spring) {
  Status valid = validateParticleRef(spring.particle, "particle");
  if (valid && !spring.anchor.allFinite()) valid = Status::error("anchor is not finite");
  if (valid) valid = checkSpringValues(spring.stiffness, spring.rest_length, spring.damping);
  if (!valid) return valid;
  return addGenerator(generators_.anchored_springs, spring);
}

Result<GeneratorId> World::addBungee(const Bungee& bungee) {
  Status valid = validateParticleRef(bungee.a, "a");
  if (valid) valid = validateParticleRef(bungee.b, "b");
  if (valid && bungee.a == bungee.b) valid = Status::error("a and b must be different particles");
  if (valid) valid = checkSpringValues(bungee.stiffness, bungee.rest_length, bungee.damping);
  if (!valid) return valid;
  return addGenerator(generators_.bungees, bungee);
}

Result<GeneratorId> World::addAnchoredBungee(const AnchoredBungee& bungee) {
  Status valid = validateParticleRef(bungee.particle, "particle");
  if (valid && !bungee.anchor.allFinite()) valid = Status::error("anchor is not finite");
  if (valid) valid = checkSpringValues(bungee.stiffness, bungee.rest_length, bungee.damping);
  if (!valid) return valid;
  return addGenerator(generators_.anchored_bungees, bungee);
}

Result<GeneratorId> World::addBuoyancy(const Buoyancy& buoyancy) {
  Status valid = validateParticleRef(buoyancy.particle, "particle");
  if (valid && (!std::isfinite(buoyancy.max_depth) || buoyancy.max_depth <= 0.0)) {
    valid = Status::error("max_depth must be finite and > 0");
  }
  if (valid && !finiteNonNegative(buoyancy.volume)) {
    valid = Status::error("volume must be finite and >= 0");
  }
  if (valid && !finiteNonNegative(buoyancy.liquid_density)) {
    valid = Status::error("liquid_density must be finite and >= 0");
  }
  if (valid && !std::isfinite(buoyancy.surface_height)) {
    valid = Status::error("surface_height is not finite");
  }
  if (valid && (!buoyancy.up.allFinite() || buoyancy.up.norm() < 1e-9)) {
    valid = Status::error("up must be a finite non-zero vector");
  }
  if (!valid) return valid;
  Buoyancy normalised = buoyancy;
  normalised.up.normalize();
  return addGenerator(generators_.buoyancies, normalised);
}

Result<GeneratorId> World::addStiffSpring(const StiffSpring& spring) {
  Status valid = validateParticleRef(spring.particle, "particle");
  if (valid && !spring.anchor.allFinite()) valid = Status::error("anchor is not finite");
  if (valid) valid = checkSpringValues(spring.stiffness, 0.0, spring.damping);
  if (!valid) return valid;
  return addGenerator(generators_.stiff_springs, spring);
}

Status World::removeGenerator(const GeneratorId id) {
  const bool removed =
      eraseById(generators_.drags, id) || eraseById(generators_.springs, id) ||
      eraseById(generators_.anchored_springs, id) || eraseById(generators_.bungees, id) ||
      eraseById(generators_.anchored_bungees, id) || eraseById(generators_.buoyancies, id) ||
      eraseById(generators_.stiff_springs, id) || eraseById(links_.cables, id) ||
      eraseById(links_.rods, id) || eraseById(links_.anchored_cables, id) ||
      eraseById(links_.anchored_rods, id);
  if (!removed) return Status::error("no force generator or link with id " + std::to_string(id));
  invalidateCaches();
  return Status::ok();
}

void World::clear() {
  particles_.clear();
  generators_.clear();
  colliders_.clear();
  links_.clear();
  slot_has_material_.assign(slot_has_material_.size(), 0);
  custom_material_count_ = 0;
  last_contact_stats_ = ContactStats{};
  if (contact_workspace_) contact_workspace_->resolver.clearWarmStart();
  time_origin_ = 0.0;
  steps_since_origin_ = 0;
  step_count_ = 0;
  accumulator_ = 0.0;
  has_external_force_ = false;
  last_divergence_.reset();
  divergence_count_ = 0;
  paused_ = false;
  invalidateCaches();
}

void World::invalidateCaches() {
  verlet_history_h_ = 0.0;
  acceleration_valid_ = false;
  forces_ahead_valid_ = false;
  energy_known_ = false;
}

void World::refreshDenseSprings() {
  if (denseSprings()) return;
  dense_springs_ = resolveDenseSprings(generators_, particles_);
  dense_springs_layout_ = particles_.layoutVersion();
  dense_springs_generators_ = generators_.size();
  dense_springs_next_id_ = next_generator_id_;
}

const DenseSprings* World::denseSprings() const {
  // Springs only change through add (a new id), remove (fewer generators) and clear; dense
  // indices only through the store's layout.
  const bool valid = dense_springs_layout_ == particles_.layoutVersion() &&
                     dense_springs_generators_ == generators_.size() &&
                     dense_springs_next_id_ == next_generator_id_;
  return valid ? &dense_springs_ : nullptr;
}

void World::resizeScratch() {
  const Eigen::Index n = static_cast<Eigen::Index>(particles_.size());
  if (acceleration_.cols() != n) {
    acceleration_.setZero(3, n);
    acceleration_valid_ = false;
  }
}

void World::refreshDampingFactors(const Real h) {
  const std::size_t n = particles_.size();
  if (damping_factor_h_ == h && damping_factor_version_ == particles_.dampingVersion() &&
      static_cast<std::size_t>(damping_factor_.size()) == n) {
    return;
  }
  const auto damping = particles_.dampings();
  damping_factor_.resize(static_cast<Eigen::Index>(n));
  for (std::size_t i = 0; i < n; ++i) damping_factor_[i] = std::pow(damping[i], h);
  damping_factor_h_ = h;
  damping_factor_version_ = particles_.dampingVersion();
}

void World::computeAccelerations(const Eigen::Ref<const Vec3Array>& x,
                                 const Eigen::Ref<const Vec3Array>& v, const Real h,
                                 Eigen::Ref<Vec3Array> out) const {
  const std::size_t n = particles_.size();
  const auto inverse_mass = particles_.inverseMasses();
  const auto mobility = particles_.mobility();
  const auto own_acceleration = particles_.accelerations();
  const Vec3 g = config_.gravity;
  if (generators_.empty() && !has_external_force_) {
    for (std::size_t i = 0; i < n; ++i) out.col(i) = mobility[i] * (g + own_acceleration.col(i));
    return;
  }
  if (has_external_force_) {
    out = particles_.forces();
  } else {
    out.setZero();
  }
  accumulateGeneratorForces(generators_, particles_, x, v, g.norm(), h, out, denseSprings());
  // a = F/m + g + a_own, zero for immovable particles
  for (std::size_t i = 0; i < n; ++i) {
    out.col(i) = out.col(i) * inverse_mass[i] + mobility[i] * (g + own_acceleration.col(i));
  }
}

void World::step() {
  if (paused_) return;
  refreshDenseSprings();
  const int substeps = stabilityReport().substeps_used;
  substeps_used_ = substeps;
  const std::uint64_t divergences_before = divergence_count_;
  const bool guard_energy = energyGuardApplies();
  if (guard_energy && !energy_known_) {
    std::tie(free_energy_, gravitational_energy_) = guardEnergies();
    energy_ = free_energy_ + gravitational_energy_;
    steps_since_energy_reference_ = 0;
    energy_known_ = true;
  }
  const Real h = config_.dt / static_cast<Real>(substeps);
  dropped_this_step_ = 0;
  pass_energies_valid_ = false;
  for (int s = 0; s < substeps; ++s) substep(h);
  if (has_external_force_) {
    particles_.forces().setZero();
    has_external_force_ = false;
    acceleration_valid_ = false;
  }
  ++steps_since_origin_;
  ++step_count_;
  // Contact resolution and links remove energy but their position corrections may add a little:
  // a step with contacts takes a new reference instead of being judged.
  const bool had_contacts = contactsActive() && last_contact_stats_.contacts > 0;
  if (guard_energy && !had_contacts) {
    checkEnergyGrowth(config_.dt);
  } else {
    detectDivergence();
    energy_known_ = false;
  }
  if (divergence_count_ != divergences_before) applyDivergencePolicy();
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

void World::substep(const Real h) {
  resizeScratch();
  refreshDampingFactors(h);
  const bool contacts = contactsActive();
  if (contacts && collision_settings_.continuous) {
    if (!contact_workspace_) contact_workspace_ = std::make_unique<ContactWorkspace>();
    contact_workspace_->substep_start = particles_.positions();
  }
  switch (config_.integrator) {
    case Integrator::kExplicitEuler:
      integrateExplicitEuler(h);
      break;
    case Integrator::kSemiImplicitEuler:
      integrateSemiImplicitEuler(h);
      break;
    case Integrator::kPositionVerlet:
      integratePositionVerlet(h);
      break;
    case Integrator::kVelocityVerlet:
      integrateVelocityVerlet(h);
      break;
    case Integrator::kRk4:
      integrateRk4(h);
      break;
    case Integrator::kImplicitEuler:
      integrateImplicitEuler(h);
      break;
  }
  if (contacts) {
    resolveContacts(h);
  } else {
    last_contact_stats_ = ContactStats{};
  }
}

void World::detectDivergence() {
  const auto x = particles_.positions();
  const auto v = particles_.velocities();
  if (allFinite(x.data(), v.data(), 3 * particles_.size())) return;
  for (std::size_t i = 0; i < particles_.size(); ++i) {
    const bool bad_x = !x.col(i).allFinite();
    if (bad_x || !v.col(i).allFinite()) {
      last_divergence_ =
          DivergenceEvent{step_count_, time(), particles_.idAt(i),
                          bad_x ? "position is not finite" : "velocity is not finite"};
      ++divergence_count_;
      return;
    }
  }
}

World::StabilityInputs World::stabilityInputs() const {
  // Particle add and remove also bump the damping version; masses only change through them.
  return {particles_.size(), generators_.size(), next_generator_id_, particles_.dampingVersion(),
          config_.dt,        config_.substeps,   config_.integrator};
}

const StabilityReport& World::stabilityReport() const {
  const StabilityInputs inputs = stabilityInputs();
  if (stability_dirty_ || !(inputs == stability_inputs_)) {
    stability_inputs_ = inputs;
    stability_report_ =
        analyseStability(generators_, particles_, config_.integrator, config_.dt, config_.substeps);
    const auto own_acceleration = particles_.accelerations();
    const auto inverse_mass = particles_.inverseMasses();
    movable_mass_ = 0.0;
    mass_.setZero(static_cast<Eigen::Index>(particles_.size()));
    bool own = false;
    for (std::size_t i = 0; i < particles_.size(); ++i) {
      if (inverse_mass[i] <= 0.0) continue;
      mass_[i] = 1.0 / inverse_mass[i];
      movable_mass_ += mass_[i];
      own = own || !own_acceleration.col(i).isZero(0.0);
    }
    has_uncounted_work_ = own || !generators_.buoyancies.empty();
    stability_dirty_ = false;
  }
  // `stable` stays about config().substeps (the warning); substeps_used is what step() takes.
  const bool raise = config_.auto_substep && !stability_report_.stable &&
                     stability_report_.substeps_needed > config_.substeps;
  stability_report_.substeps_used = raise ? stability_report_.substeps_needed : config_.substeps;
  return stability_report_;
}

bool World::energyGuardApplies() const {
  // Without generators every acceleration is constant: nothing can run away.
  return config_.energy_growth_limit > 0.0 && !generators_.empty() && !has_external_force_ &&
         !has_uncounted_work_;
}

void World::checkEnergyGrowth(const Real dt) {
  ++steps_since_energy_reference_;
  const StepEnergies energies = guardEnergiesAfterStep();
  if (!energies.finite) {
    // Not judged: a non-finite value is the divergence to report (and the energy meaningless).
    energy_known_ = false;
    detectDivergence();
    return;
  }
  const Real free_energy = energies.free;
  const Real gravitational = energies.gravitational;
  const Real energy = free_energy + gravitational;
  // Allowances: truncation of a constant force (explicit Euler gains m g^2 h^2 / 2 a substep),
  // and round-off in the sums.
  const Real truncation = movable_mass_ * config_.gravity.squaredNorm() * dt * dt *
                          static_cast<Real>(steps_since_energy_reference_);
  const Real round_off =
      1e-9 * (std::abs(gravitational_energy_) + std::abs(gravitational) + free_energy_);
  const Real bound = energy_ + config_.energy_growth_limit * free_energy_ + truncation + round_off;
  if (energy <= bound) return;
  // Name the particle with the most kinetic energy: the runaway.
  const auto v = particles_.velocities();
  std::size_t fastest = 0;
  Real most = -1.0;
  for (std::size_t i = 0; i < particles_.size(); ++i) {
    const Real e = 0.5 * mass_[i] * v.col(i).squaredNorm();
    if (e > most) {
      most = e;
      fastest = i;
    }
  }
  last_divergence_ = DivergenceEvent{
      step_count_, time(), particles_.idAt(fastest),
      "energy grew from " + std::to_string(energy_) + " J to " + std::to_string(energy) +
          " J without external work (bound " + std::to_string(bound) + " J)"};
  ++divergence_count_;
  energy_known_ = false;
}

World::ParticleEnergies World::particleEnergies() const {
  const Real g[3] = {config_.gravity.x(), config_.gravity.y(), config_.gravity.z()};
  EnergyAccumulator sums;
  accumulateParticleEnergies(particles_.size(), mass_.data(), particles_.positions().data(),
                             particles_.velocities().data(), sums);
  return sums.sums(g);
}

std::pair<Real, Real> World::guardEnergies() const {
  const ParticleEnergies sums = particleEnergies();
  return {
      0.5 * sums.kinetic_twice + generatorPotentialEnergy(generators_, particles_, denseSprings()),
      sums.gravitational};
}

bool World::forcesAheadPossible() const {
  // The next step must start from this state with one substep of the same h: no contact phase
  // (it would move particles after the forces), no external force, dense springs up to date.
  return config_.integrator == Integrator::kSemiImplicitEuler && substeps_used_ == 1 &&
         config_.substeps == 1 && !has_external_force_ && !contactsActive() &&
         denseSprings() != nullptr;
}

World::StepEnergies World::guardEnergiesAfterStep() {
  const ParticleEnergies sums = pass_energies_valid_ ? pass_energies_ : particleEnergies();
  StepEnergies energies;
  energies.gravitational = sums.gravitational;
  energies.finite = sums.finite();
  if (!energies.finite) return energies;
  if (!forcesAheadPossible()) {
    energies.free = 0.5 * sums.kinetic_twice +
                    generatorPotentialEnergy(generators_, particles_, denseSprings());
    return energies;
  }
  // The forces integrateSemiImplicitEuler would compute first thing next step, the same calls on
  // the same state, so the same bits; their spring lengths give the elastic energy.
  const auto x = particles_.positions();
  const auto v = particles_.velocities();
  forces_ahead_.setZero(3, x.cols());
  Real elastic = 0.0;
  accumulateGeneratorForces(generators_, particles_, x, v, config_.gravity.norm(), config_.dt,
                            forces_ahead_, denseSprings(), &elastic);
  forces_ahead_valid_ = true;
  energies.free = 0.5 * sums.kinetic_twice + elastic;
  return energies;
}

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
      const std::optional<DivergenceEvent> event = last_divergence_;
      const std::uint64_t count = divergence_count_;
      const std::shared_ptr<const World> snapshot = reset_snapshot_;
      *this = *snapshot;
      last_divergence_ = event;
      divergence_count_ = count;
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

ConstVec3Map World::lastAccelerations() const {
  return ConstVec3Map(acceleration_.data(), 3, acceleration_.cols());
}

Real World::kineticEnergy() const {
  const auto v = particles_.velocities();
  const auto inverse_mass = particles_.inverseMasses();
  Real energy = 0.0;
  for (std::size_t i = 0; i < particles_.size(); ++i) {
    if (inverse_mass[i] > 0.0) energy += 0.5 * v.col(i).squaredNorm() / inverse_mass[i];
  }
  return energy;
}

Real World::gravitationalEnergy() const {
  const auto x = particles_.positions();
  const auto inverse_mass = particles_.inverseMasses();
  Real energy = 0.0;
  for (std::size_t i = 0; i < particles_.size(); ++i) {
    if (inverse_mass[i] > 0.0) energy -= config_.gravity.dot(x.col(i)) / inverse_mass[i];
  }
  return energy;
}

Real World::springEnergy() const { return generatorPotentialEnergy(generators_, particles_); }

Vec3 World::linearMomentum() const {
  const auto v = particles_.velocities();
  const auto inverse_mass = particles_.inverseMasses();
  Vec3 momentum = Vec3::Zero();
  for (std::size_t i = 0; i < particles_.size(); ++i) {
    if (inverse_mass[i] > 0.0) momentum += v.col(i) / inverse_mass[i];
  }
  return momentum;
}

std::uint64_t World::stateHash() const {
  StateHasher hasher;
  hasher.add(static_cast<std::uint64_t>(particles_.size()));
  hasher.add(step_count_);
  hasher.add(time());
  const auto x = particles_.positions();
  const auto v = particles_.velocities();
  const auto previous = particles_.previousPositions();
  for (std::size_t i = 0; i < particles_.size(); ++i) {
    hasher.add(particles_.idAt(i).packed());
    hasher.add(x.col(i));
    hasher.add(v.col(i));
    if (config_.integrator == Integrator::kPositionVerlet) hasher.add(previous.col(i));
  }
  // The impulses contacts and links carry into the next substep are state too.
  if (contact_workspace_) contact_workspace_->resolver.addToHash(hasher);
  return hasher.value();
}

}  // namespace engine
}  // namespace mass_aggregate_sim
