#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "mass_aggregate_sim/engine/colliders.h"
#include "mass_aggregate_sim/engine/collision_settings.h"
#include "mass_aggregate_sim/engine/force_evaluation.h"
#include "mass_aggregate_sim/engine/force_generators.h"
#include "mass_aggregate_sim/engine/links.h"
#include "mass_aggregate_sim/engine/particle_energies.h"
#include "mass_aggregate_sim/engine/particle_store.h"
#include "mass_aggregate_sim/engine/queries.h"
#include "mass_aggregate_sim/engine/stability.h"
#include "mass_aggregate_sim/engine/status.h"
#include "mass_aggregate_sim/engine/types.h"
#include "mass_aggregate_sim/engine/world_config.h"

namespace mass_aggregate_sim {
namespace engine {

class ImplicitEulerSolver;
struct ContactWorkspace;

// A divergence found after a step: a non-finite position or velocity (the first such particle), or
// energy growing beyond the guard's bound (the particle with the most kinetic energy).
struct DivergenceEvent {
  std::uint64_t step = 0;
  Real time = 0.0;
  ParticleId particle;
  std::string what;
};

// The force a cable or rod applied in the last substep, from its constraint's total impulse J over
// that substep of length h: tension = J / h (N). The impulse acts on the link's first particle
// (a, or the anchored link's particle) along the unit vector towards its other end, so
// tension > 0 pulls the ends together (a taut cable, a stretched rod), tension < 0 pushes them
// apart (only a rod, in compression), and 0 means the link did not act (a slack cable).
struct LinkTension {
  GeneratorId id = 0;
  Real tension = 0.0;
};

// The particle world: particles, force generators, and a fixed-step integrator. Time is passed in
// (step, advance), never read from a clock. All mutation goes through this class so the caches it
// keeps (d^dt, Verlet history, last acceleration) stay consistent; the same calls in the same
// order give bit-identical states.
class World {
 public:
  explicit World(const WorldConfig& config = WorldConfig{});
  ~World();
  World(const World& other);
  World& operator=(const World& other);
  World(World&&) noexcept;
  World& operator=(World&&) noexcept;

  const WorldConfig& config() const { return config_; }
  // Refuses an invalid config and keeps the old one.
  Status setConfig(const WorldConfig& config);

  // --- particles ---
  Result<ParticleId> addParticle(const ParticleSpec& spec);
  // Also removes every force generator and link that refers to the particle.
  Status removeParticle(ParticleId id);
  Status setPosition(ParticleId id, const Vec3& position);
  Status setVelocity(ParticleId id, const Vec3& velocity);
  // dv = J / m; refused for an immovable particle.
  Status applyImpulse(ParticleId id, const Vec3& impulse);
  // Adds to the external force the particle feels during the next step only.
  Status addForce(ParticleId id, const Vec3& force);
  const ParticleStore& particles() const { return particles_; }

  // --- force generators (each validated: live distinct particles, finite values, k, c >= 0) ---
  Result<GeneratorId> addDrag(const Drag& drag);
  Result<GeneratorId> addSpring(const Spring& spring);
  Result<GeneratorId> addAnchoredSpring(const AnchoredSpring& spring);
  Result<GeneratorId> addBungee(const Bungee& bungee);
  Result<GeneratorId> addAnchoredBungee(const AnchoredBungee& bungee);
  Result<GeneratorId> addBuoyancy(const Buoyancy& buoyancy);
  Result<GeneratorId> addStiffSpring(const StiffSpring& spring);
  // Removes a force generator or a link (they share one id space).
  Status removeGenerator(GeneratorId id);
  const ForceGenerators& generators() const { return generators_; }

  // --- static colliders (particles collide with them as spheres of their radius) ---
  // Each validated: finite values, positive sizes, restitution in [0, 1], friction >= 0; plane
  // normals and box orientations are normalised.
  Result<ColliderId> addPlane(const PlaneCollider& plane);
  Result<ColliderId> addSphere(const SphereCollider& sphere);
  Result<ColliderId> addBox(const BoxCollider& box);
  Result<ColliderId> addCapsule(const CapsuleCollider& capsule);
  Status removeCollider(ColliderId id);
  const Colliders& colliders() const { return colliders_; }

  // --- links: hard constraints between particles or to anchors, ids from the generator space ---
  Result<GeneratorId> addCable(const Cable& cable);
  Result<GeneratorId> addRod(const Rod& rod);
  Result<GeneratorId> addAnchoredCable(const AnchoredCable& cable);
  Result<GeneratorId> addAnchoredRod(const AnchoredRod& rod);
  const Links& links() const { return links_; }
  // Every live link's tension in the last substep (LinkTension), sorted by id. A link added since
  // the last step, or every link after a particle was removed (the resolver forgets its warm
  // start then), reads 0 until the next step. Reads what the resolver kept for warm starting:
  // no work during the step, O(links log links) here.
  std::vector<LinkTension> linkTensions() const;

  // --- contacts ---
  Status setCollisionSettings(const CollisionSettings& settings);
  const CollisionSettings& collisionSettings() const { return collision_settings_; }
  // A particle's own material for particle-particle contacts; a pair combines the two (mean
  // restitution, geometric mean friction). Particles without one use the collision settings'.
  Status setParticleMaterial(ParticleId id, const Material& material);
  // Diagnostics of the contact phase of the last substep (dropped: summed over the last step).
  const ContactStats& lastContactStats() const { return last_contact_stats_; }

  // --- queries ---
  std::optional<RayHit> raycast(const Vec3& origin, const Vec3& direction, Real max_distance) const;
  // Particles whose sphere overlaps the given sphere / axis-aligned box.
  std::vector<ParticleId> overlapSphere(const Vec3& center, Real radius) const;
  std::vector<ParticleId> overlapBox(const Vec3& center, const Vec3& half_extents) const;

  // Removes all particles, generators, links and colliders; time goes back to zero. Settings stay.
  void clear();

  // --- time ---
  // One fixed step of dt, split into config().substeps substeps.
  void step();
  // Feeds a variable frame time (clamped to [0, max_frame_time]) into the accumulator and takes as
  // many fixed steps as fit. Returns how many it took; the remainder waits for the next call.
  int advance(Real frame_time);
  // Fraction of a step left in the accumulator, for interpolating what is shown.
  Real accumulatorAlpha() const { return accumulator_ / config_.dt; }
  Real time() const { return time_origin_ + static_cast<Real>(steps_since_origin_) * config_.dt; }
  std::uint64_t stepCount() const { return step_count_; }

  // --- measurements ---
  Real kineticEnergy() const;
  // -sum m g.x over movable particles (zero at the origin).
  Real gravitationalEnergy() const;
  Real springEnergy() const;
  Real totalEnergy() const { return kineticEnergy() + gravitationalEnergy() + springEnergy(); }
  Vec3 linearMomentum() const;
  // Hash of the full dynamic state (ids, positions, velocities, Verlet history, time): equal
  // hashes mean bit-identical states.
  std::uint64_t stateHash() const;

  // Divergence: a non-finite position or velocity after a step. Detected in the step that
  // produced it; the latest event is kept and the count grows.
  const std::optional<DivergenceEvent>& lastDivergence() const { return last_divergence_; }
  std::uint64_t divergenceCount() const { return divergence_count_; }

  // Acceleration each particle had in the last substep (the average over RK4's stages).
  ConstVec3Map lastAccelerations() const;

  // --- stability guard (stability.h, WorldConfig::auto_substep, divergence_policy) ---
  // The stiffest spring against the integrator's limit at the current dt and substeps; kept up to
  // date with the scene. !stable is the warning: it names the spring, its omega*h and stable dt.
  const StabilityReport& stabilityReport() const;
  // Substeps the last step took (auto_substep can raise config().substeps).
  int substepsUsed() const { return substeps_used_; }
  // True after a divergence under DivergencePolicy::kPause (or kReset without a snapshot): step()
  // and advance() do nothing until resume().
  bool paused() const { return paused_; }
  void resume() { paused_ = false; }
  // Keeps a copy of the whole world as it is now, for DivergencePolicy::kReset.
  void setResetSnapshot();
  void clearResetSnapshot() { reset_snapshot_.reset(); }
  bool hasResetSnapshot() const { return reset_snapshot_ != nullptr; }

 private:
  template <typename Generator>
  Result<GeneratorId> addGenerator(std::vector<Generator>& kind, Generator generator);
  Status validateParticleRef(ParticleId id, const char* field) const;
  void invalidateCaches();
  // The springs and bungees with dense indices: rebuilt at the start of a step when the generators
  // or the particles' layout changed; nullptr while stale (callers then look ids up).
  void refreshDenseSprings();
  const DenseSprings* denseSprings() const;
  void resizeScratch();
  void refreshDampingFactors(Real h);
  // Total acceleration at (x, v): generators, external forces, gravity, per-particle acceleration.
  void computeAccelerations(const Eigen::Ref<const Vec3Array>& x,
                            const Eigen::Ref<const Vec3Array>& v, Real h,
                            Eigen::Ref<Vec3Array> out) const;
  void substep(Real h);
  void integrateExplicitEuler(Real h);
  void integrateSemiImplicitEuler(Real h);
  void integratePositionVerlet(Real h);
  void integrateVelocityVerlet(Real h);
  void integrateRk4(Real h);
  void integrateImplicitEuler(Real h);
  void detectDivergence();
  // Energy guard bookkeeping around one step; see WorldConfig::energy_growth_limit.
  bool energyGuardApplies() const;
  // Also detects a non-finite position or velocity (as detectDivergence) in the same pass.
  void checkEnergyGrowth(Real dt);
  // One pass over the particles: twice the kinetic energy and the gravitational energy (cached
  // masses, no division), and sum(0 * x) + sum(0 * v), which is 0 unless a value is not finite.
  using ParticleEnergies = engine::ParticleEnergies;
  ParticleEnergies particleEnergies() const;
  // The sums of the last semi-implicit Euler pass, when it made them (see substep()).
  ParticleEnergies pass_energies_;
  bool pass_energies_valid_ = false;
  // Kinetic + elastic and gravitational energy.
  std::pair<Real, Real> guardEnergies() const;
  // The same after a step, with the finite probe; where it can, it evaluates the next step's forces
  // at the same time and takes the elastic energy from their spring lengths.
  struct StepEnergies {
    Real free = 0.0;
    Real gravitational = 0.0;
    bool finite = true;
  };
  StepEnergies guardEnergiesAfterStep();
  bool forcesAheadPossible() const;
  void applyDivergencePolicy();
  // Contact phase (world_contacts.cpp), run after each substep's integration.
  bool contactsActive() const;
  void resolveContacts(Real h);
  void sweepParticles(ContactWorkspace& workspace);
  void generateContacts(ContactWorkspace& workspace, std::size_t& dropped);
  // The collider contacts of particles [begin, end), appended to workspace.contacts; true when
  // one of them met two or more colliders.
  bool generateColliderContacts(ContactWorkspace& workspace, std::size_t begin, std::size_t end,
                                std::size_t& dropped);
  void resolveColliderContactsInParts(ContactWorkspace& workspace, Real h);
  void buildLinkedPairs(ContactWorkspace& workspace) const;
  Material particleMaterial(std::size_t dense) const;
  Result<ColliderId> nextColliderId();

  WorldConfig config_;
  ParticleStore particles_;
  ForceGenerators generators_;
  GeneratorId next_generator_id_ = 1;

  Real time_origin_ = 0.0;
  std::uint64_t steps_since_origin_ = 0;
  std::uint64_t step_count_ = 0;
  Real accumulator_ = 0.0;

  bool has_external_force_ = false;
  // Cached d^dt per particle: valid for this substep length and damping version.
  ScalarArray damping_factor_;
  Real damping_factor_h_ = 0.0;
  std::uint64_t damping_factor_version_ = ~std::uint64_t{0};
  // Position Verlet's previous positions are valid for this substep length (0: re-seed them).
  Real verlet_history_h_ = 0.0;
  // Velocity Verlet reuses the last acceleration when nothing changed since.
  bool acceleration_valid_ = false;

  Vec3Array acceleration_;
  Vec3Array scratch_x_;
  Vec3Array scratch_v_;
  Vec3Array stage_a_[3];
  std::unique_ptr<ImplicitEulerSolver> implicit_solver_;

  std::optional<DivergenceEvent> last_divergence_;
  std::uint64_t divergence_count_ = 0;

  // Stability guard: the report is recomputed lazily when what it depends on (particles and
  // their masses, springs, dt, substeps, integrator) may have changed, not on every set or add.
  struct StabilityInputs {
    std::size_t particles = 0;
    std::size_t generators = 0;
    GeneratorId next_generator_id = 0;
    std::uint64_t damping_version = 0;
    Real dt = 0.0;
    int substeps = 0;
    Integrator integrator = Integrator::kSemiImplicitEuler;
    bool operator==(const StabilityInputs& o) const {
      return particles == o.particles && generators == o.generators &&
             next_generator_id == o.next_generator_id && damping_version == o.damping_version &&
             dt == o.dt && substeps == o.substeps && integrator == o.integrator;
    }
  };
  StabilityInputs stabilityInputs() const;
  mutable StabilityReport stability_report_;
  mutable bool stability_dirty_ = true;
  mutable StabilityInputs stability_inputs_;
  // Set with the report: per-particle accelerations or buoyancy add work the energy omits.
  mutable bool has_uncounted_work_ = false;
  mutable Real movable_mass_ = 0.0;
  mutable ScalarArray mass_;  // 0 for immovable particles
  int substeps_used_ = 1;
  // The energy guard's reference: the state at the first step after the last scene change.
  bool energy_known_ = false;
  Real energy_ = 0.0;
  Real free_energy_ = 0.0;  // kinetic + elastic
  Real gravitational_energy_ = 0.0;
  std::uint64_t steps_since_energy_reference_ = 0;
  bool paused_ = false;
  std::shared_ptr<const World> reset_snapshot_;
  Colliders colliders_;
  ColliderId next_collider_id_ = 1;
  Links links_;
  CollisionSettings collision_settings_;
  ContactStats last_contact_stats_;
  std::size_t dropped_this_step_ = 0;
  // Particle materials by slot (ParticleId::index), so they survive the store's dense moves.
  std::vector<Material> slot_material_;
  std::vector<std::uint8_t> slot_has_material_;
  std::size_t custom_material_count_ = 0;
  // Semi-implicit Euler under the energy guard: the generator forces at the state a step ended
  // in, computed with the guard's elastic energy and used by the next step unless anything
  // changed since (invalidateCaches). Not copied: a copy recomputes them.
  Vec3Array forces_ahead_;
  bool forces_ahead_valid_ = false;
  DenseSprings dense_springs_;
  // What dense_springs_ was built from; a copied world starts stale and rebuilds.
  std::uint64_t dense_springs_layout_ = ~std::uint64_t{0};
  std::size_t dense_springs_generators_ = 0;
  GeneratorId dense_springs_next_id_ = 0;
  // The contact phase's buffers and warm-start impulses; created on first use.
  std::unique_ptr<ContactWorkspace> contact_workspace_;
};

}  // namespace engine
}  // namespace mass_aggregate_sim
