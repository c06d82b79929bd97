#pragma once

#include <algorithm>
#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "mass_aggregate_sim/engine/bodies/body_contact_report.h"
#include "mass_aggregate_sim/engine/bodies/body_settings.h"
#include "mass_aggregate_sim/engine/bodies/body_store.h"
#include "mass_aggregate_sim/engine/collision/colliders.h"
#include "mass_aggregate_sim/engine/collision/collision_settings.h"
#include "mass_aggregate_sim/engine/collision/particle_materials.h"
#include "mass_aggregate_sim/engine/collision/queries.h"
#include "mass_aggregate_sim/engine/core/owned.h"
#include "mass_aggregate_sim/engine/core/particle_store.h"
#include "mass_aggregate_sim/engine/core/status.h"
#include "mass_aggregate_sim/engine/core/types.h"
#include "mass_aggregate_sim/engine/forces/body_force_generators.h"
#include "mass_aggregate_sim/engine/forces/force_generators.h"
#include "mass_aggregate_sim/engine/joints/joints.h"
#include "mass_aggregate_sim/engine/solver/links.h"
#include "mass_aggregate_sim/engine/world/stability.h"
#include "mass_aggregate_sim/engine/world/world_config.h"

namespace mass_aggregate_sim {
namespace engine {

// A divergence found after a step: a non-finite position or velocity (the first such particle or
// body), or energy growing beyond the guard's bound (the particle or body with the most kinetic
// energy). One of particle and body is valid.
struct DivergenceEvent {
  std::uint64_t step = 0;
  Real time = 0.0;
  ParticleId particle;
  BodyId body;
  std::string what;
};

// The force a cable or rod applied in the last substep, from its constraint's total impulse J over
// that substep of length h: tension = J / h (N). The impulse acts on the link's first particle
// (a) along the unit vector towards its other end, so tension > 0 pulls the ends together (a taut
// cable, a stretched rod), tension < 0 pushes them apart (only a rod, in compression), and 0 means
// the link did not act (a slack cable).
struct LinkTension {
  GeneratorId id = 0;
  Real tension = 0.0;
};

// A config validateConfig() refuses, given to World's constructor.
class InvalidConfig : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// The state the world keeps about its integrator, its contacts and its guards between steps.
struct IntegratorState;
struct ContactWorkspace;
struct GuardState;
struct BodyWorkspace;
// What the world derives from its state to save work (never state: a copy derives it again).
struct StepCaches;
class StepContext;

// The particle world: particles, force generators, links, colliders and a fixed-step integrator.
// Time is passed in (step, advance), never read from a clock. All mutation goes through this
// class and is validated here (each kind validates itself); the same calls in the same order give
// bit-identical states. A copy is a full, independent world that steps on exactly as the original
// would.
class World {
 public:
  // The default config (always valid).
  World();
  // Throws InvalidConfig, with validateConfig's message, when the config is invalid: a world
  // never runs on settings other than those it was given. create() is the non-throwing form.
  explicit World(const WorldConfig& config);
  static Result<World> create(const WorldConfig& config);
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

  // --- force generators (ForceKinds: Drag, Spring, Buoyancy, StiffSpring) and links (LinkKinds:
  // Cable, Rod); one id space. Each is validated by its kind (ForceKind<K>::validate,
  // LinkKind<K>::validate): live distinct particles, finite values in range. ---
  template <typename Kind>
  Result<GeneratorId> addGenerator(Kind generator);
  // What addGenerator would say, without adding it (a request of several can check them all).
  template <typename Kind>
  Status checkGenerator(Kind generator) const {
    return ForceKind<Kind>::validate(generator, particles_);
  }
  template <typename Kind>
  Result<GeneratorId> addLink(Kind link);
  // Removes a force generator (on particles or on bodies) or a link.
  Status removeGenerator(GeneratorId id);
  const ForceGenerators& generators() const { return generators_; }
  const Links& links() const { return links_; }
  // Every live link's tension in the last substep (LinkTension), sorted by id. A link added since
  // the last step, or every link after a particle was removed (the resolver forgets its warm
  // start then), reads 0 until the next step. Reads what the resolver kept for warm starting:
  // no work during the step, O(links log links) here.
  std::vector<LinkTension> linkTensions() const;

  // --- static colliders (ShapeKinds); particles collide with them as spheres of their radius.
  // Each is validated and normalised by its kind (ShapeKind<K>::validate). ---
  template <typename Shape>
  Result<ColliderId> addCollider(Shape shape);
  Status removeCollider(ColliderId id);
  const Colliders& colliders() const { return colliders_; }

  // --- rigid bodies (bodies/): a second kind of body in the same world, stepped by the same
  // stages; a world without bodies pays nothing for them. Every request on a body wakes it. ---
  // Refused (nothing added) when the spec or its mass properties are invalid.
  Result<BodyId> addBody(const BodySpec& spec);
  // Also removes its joints and its contacts.
  Status removeBody(BodyId id);
  // Moves the body's frame to pose (velocities kept).
  Status setBodyPose(BodyId id, const Transform& pose);
  // Velocities of the centre of mass, world frame.
  Status setBodyVelocity(BodyId id, const Vec3& linear, const Vec3& angular);
  // A force at a world point for the next step: F on the centre of mass and (p - c) x F about it.
  Status addBodyForce(BodyId id, const Vec3& force, const Vec3& point);
  Status addBodyTorque(BodyId id, const Vec3& torque);
  // dv = J / m and dw = I^-1 ((p - c) x J) for a linear impulse J at world point p, plus
  // dw = I^-1 L for an angular impulse L; refused for a body that is not dynamic.
  Status applyBodyImpulse(BodyId id, const Vec3& impulse, const Vec3& point,
                          const Vec3& angular_impulse = Vec3::Zero());
  Status wakeBody(BodyId id);
  const BodyStore& bodies() const { return bodies_; }
  // Settings that differ from the current ones wake every body (a sleeping pile may no longer
  // rest under them); the same settings change nothing.
  Status setBodySettings(const BodySettings& settings);
  const BodySettings& bodySettings() const { return body_settings_; }
  // Every body contact with at least one point, as of the last step, in the solver's order; its
  // impulses are over a substep of the last step (dt / substepsUsed()), also while the bodies
  // sleep and the step was not theirs.
  std::vector<BodyContactReport> bodyContacts() const;
  // The islands of dynamic bodies as sleeping forms them: joined by the last step's touching
  // body contacts and by joints between two bodies (fixed and kinematic bodies join none), awake
  // or asleep; a dynamic body touching nothing is one.
  std::size_t bodyIslandCount() const;
  // Force generators on bodies (BodyForceKinds: BodyDrag, PointSpring, BodyBuoyancy), in the
  // generators' id space; validated by their kind (BodyForceKind<K>::validate). Removed with
  // their bodies and particles; they wake the bodies they act on.
  template <typename Kind>
  Result<GeneratorId> addBodyGenerator(Kind generator);
  template <typename Kind>
  Status checkBodyGenerator(Kind generator) const {
    return BodyForceKind<Kind>::validate(generator, JointScene{bodies_, particles_});
  }
  const BodyForceGenerators& bodyGenerators() const { return body_generators_; }

  // --- joints (JointKinds: BallJoint, HingeJoint, FixedJoint, DistanceJoint), between two
  // bodies, a body and a particle, or a body and the world; validated by their kind. ---
  template <typename Kind>
  Result<JointId> addJoint(Kind joint);
  Status removeJoint(JointId id);
  const Joints& joints() const { return joints_; }
  // Every joint's force and torque on its end b in the body solver's last substep, sorted by id.
  std::vector<JointReaction> jointReactions() const;
  // A hinge's motor, changed while it runs.
  Status setHingeMotor(JointId id, bool enabled, Real speed, Real max_torque);

  // --- contacts ---
  Status setCollisionSettings(const CollisionSettings& settings);
  const CollisionSettings& collisionSettings() const { return collision_settings_; }
  // A particle's own material for particle-particle contacts; a pair combines the two (mean
  // restitution, geometric mean friction). Particles without one use the collision settings'.
  Status setParticleMaterial(ParticleId id, const Material& material);
  // Diagnostics of the contact phase of the last substep (dropped: summed over the last step).
  const ContactStats& lastContactStats() const { return last_contact_stats_; }

  // --- queries ---
  // The nearest particle, body or collider the ray hits (RayHit says which).
  std::optional<RayHit> raycast(const Vec3& origin, const Vec3& direction, Real max_distance) const;
  // Particles whose sphere overlaps the given sphere / axis-aligned box.
  std::vector<ParticleId> overlapSphere(const Vec3& center, Real radius) const;
  std::vector<ParticleId> overlapBox(const Vec3& center, const Vec3& half_extents) const;
  // Bodies with a shape that overlaps the given sphere / box (oriented), in dense order.
  std::vector<BodyId> bodiesOverlappingSphere(const Vec3& center, Real radius) const;
  std::vector<BodyId> bodiesOverlappingBox(const Vec3& center, const Vec3& half_extents,
                                           const Quat& orientation = Quat::Identity()) const;

  // Removes all particles, generators, links, colliders, bodies and joints; time goes back to
  // zero. Settings stay.
  void clear();

  // --- time ---
  // One fixed step of dt, split into substeps: its stages are in world/step.cpp.
  void step();
  // Feeds a variable frame time (clamped to [0, max_frame_time]) into the accumulator and takes as
  // many fixed steps as fit. Returns how many it took; the remainder waits for the next call.
  int advance(Real frame_time);
  // Fraction of a step left in the accumulator, for interpolating what is shown.
  Real accumulatorAlpha() const { return accumulator_ / config_.dt; }
  Real time() const { return time_origin_ + static_cast<Real>(steps_since_origin_) * config_.dt; }
  std::uint64_t stepCount() const { return step_count_; }

  // --- measurements (particles and bodies) ---
  // Bodies: (m v^2 + w.I w) / 2.
  Real kineticEnergy() const;
  // -sum m g.x over movable particles and dynamic bodies' centres (zero at the origin).
  Real gravitationalEnergy() const;
  Real springEnergy() const;
  Real totalEnergy() const { return kineticEnergy() + gravitationalEnergy() + springEnergy(); }
  Vec3 linearMomentum() const;
  // About the world's origin: sum x m v, plus each body's own I w.
  Vec3 angularMomentum() const;
  // Hash of the full dynamic state (ids, positions, velocities, integrator history, the impulses
  // contacts and joints carry into the next substep, bodies' orientations and sleep, time):
  // equal hashes mean bit-identical states.
  std::uint64_t stateHash() const;

  // Divergence: a non-finite position or velocity, or the energy guard, after a step. Detected
  // in the step that produced it; the latest event is kept and the count grows.
  const std::optional<DivergenceEvent>& lastDivergence() const;
  std::uint64_t divergenceCount() const;

  // --- stability guard (stability.h, WorldConfig::auto_substep, divergence_policy) ---
  // The stiffest spring against the integrator's limit at the current dt and substeps; kept up to
  // date with the scene. !stable is the warning: it names the spring, its omega*h and stable dt.
  // Springs on bodies count (analysePointSpringStability), against the bodies' substeps.
  const StabilityReport& stabilityReport() const;
  // Substeps the last step took: config().substeps (auto_substep can raise it), and at least
  // BodySettings::substeps while a body can move or holds a particle (not when every body is
  // fixed or asleep: particles resting on them then keep their own).
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
  // A new id for a generator or link; validated kinds only.
  GeneratorId nextGeneratorId() { return next_generator_id_++; }
  // The body of a request: its dense index when live, awake now; else the refusal.
  Result<std::size_t> bodyForRequest(BodyId id);
  // Checks a joint's ends: live, not the same, able to turn when the kind holds rotation, not both
  // unable to move.
  Status checkJointEnds(const JointEnd& a, const JointEnd& b, bool turns) const;
  void wakeJointEnds(const JointEnd& a, const JointEnd& b);
  void wakeBodies(const std::vector<BodyId>& bodies);
  // Removes the force generators on bodies that act on `id` (a body or a particle), waking the
  // bodies they acted on.
  template <typename Id>
  void removeBodyGeneratorsOf(Id id);
  Result<ColliderId> nextColliderId();
  // The forces, the springs' layout or the state changed: every force cache and the energy
  // guard's reference are stale (position Verlet's history is kept per particle).
  void stateChanged();

  // A step (world/step.cpp): the context its stages share, built once, and what ends it (time,
  // the guards and the divergence policy).
  StepContext beginStep();
  void finalise(StepContext& ctx);
  void applyDivergencePolicy();
  bool contactsActive() const;
  // Whether the body solver has work this step (world_bodies.cpp), so the step takes the bodies'
  // substeps; `reach`: a force generator on bodies reaches a particle (bodyForcesReachParticles).
  bool bodiesMove(bool reach) const;

  WorldConfig config_;
  ParticleStore particles_;
  ForceGenerators generators_;
  Links links_;
  GeneratorId next_generator_id_ = 1;
  // Changes whenever a generator or link is added or removed (the force stage's springs layout).
  std::uint64_t generators_version_ = 0;
  Colliders colliders_;
  ColliderId next_collider_id_ = 1;
  std::uint64_t colliders_version_ = 0;
  BodyStore bodies_;
  Joints joints_;
  JointId next_joint_id_ = 1;
  BodyForceGenerators body_generators_;
  BodySettings body_settings_;
  CollisionSettings collision_settings_;
  ParticleMaterials materials_;

  Real time_origin_ = 0.0;
  std::uint64_t steps_since_origin_ = 0;
  std::uint64_t step_count_ = 0;
  Real accumulator_ = 0.0;
  bool has_external_force_ = false;
  int substeps_used_ = 1;
  // The substep the body solver last took: the impulses its contacts and joints keep are over it.
  Real body_substep_ = 0.0;
  bool paused_ = false;
  std::shared_ptr<const World> reset_snapshot_;
  ContactStats last_contact_stats_;
  std::size_t dropped_this_step_ = 0;

  Owned<IntegratorState> integration_;
  Owned<ContactWorkspace> contacts_;
  Owned<GuardState> guard_;
  Owned<BodyWorkspace> body_ws_;  // made on first use: only worlds with bodies have one
  Derived<StepCaches> caches_;
};

template <typename Kind>
Result<GeneratorId> World::addGenerator(Kind generator) {
  const Status valid = ForceKind<Kind>::validate(generator, particles_);
  if (!valid) return valid;
  generator.id = nextGeneratorId();
  generators_.of<Kind>().push_back(generator);
  ++generators_version_;
  stateChanged();
  return generator.id;
}

template <typename Kind>
Result<GeneratorId> World::addLink(Kind link) {
  const Status valid = LinkKind<Kind>::validate(link, particles_);
  if (!valid) return valid;
  link.id = nextGeneratorId();
  links_.of<Kind>().push_back(link);
  ++generators_version_;
  stateChanged();
  return link.id;
}

template <typename Shape>
Result<ColliderId> World::addCollider(Shape shape) {
  const Status valid = ShapeKind<Shape>::validate(shape);
  if (!valid) return valid;
  const Result<ColliderId> id = nextColliderId();
  if (!id) return id;
  shape.id = *id;
  colliders_.of<Shape>().push_back(shape);
  ++colliders_version_;
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    if (bodies_.type(i) != BodyType::kFixed) bodies_.setAwake(i, true);
  }
  return id;
}

template <typename Kind>
Result<GeneratorId> World::addBodyGenerator(Kind generator) {
  const Status valid = BodyForceKind<Kind>::validate(generator, JointScene{bodies_, particles_});
  if (!valid) return valid;
  generator.id = nextGeneratorId();
  body_generators_.of<Kind>().push_back(generator);
  wakeBodies(BodyForceKind<Kind>::bodiesOf(generator));
  stateChanged();
  return generator.id;
}

template <typename Id>
void World::removeBodyGeneratorsOf(const Id id) {
  body_generators_.forEach([&](auto& kind) {
    using Kind = typename std::decay_t<decltype(kind)>::value_type;
    const auto refers = [id](const Kind& generator) {
      return BodyForceKind<Kind>::refersTo(generator, id);
    };
    for (const auto& generator : kind) {
      if (refers(generator)) wakeBodies(BodyForceKind<Kind>::bodiesOf(generator));
    }
    kind.erase(std::remove_if(kind.begin(), kind.end(), refers), kind.end());
  });
}

template <typename Kind>
Result<JointId> World::addJoint(Kind joint) {
  const Status ends = checkJointEnds(joint.a, joint.b, JointKind<Kind>::kTurns);
  if (!ends) return ends;
  const Status valid = JointKind<Kind>::validate(joint, JointScene{bodies_, particles_});
  if (!valid) return valid;
  joint.id = next_joint_id_++;
  joints_.of<Kind>().push_back(joint);
  wakeJointEnds(joint.a, joint.b);
  return joint.id;
}

}  // namespace engine
}  // namespace mass_aggregate_sim
