#pragma once

#include <cstdint>

#include "engine/forces/force_stage.h"
#include "engine/integrators/integrator_state.h"
#include "engine/world/guard_state.h"
#include "engine/world/step_caches.h"
#include "mass_aggregate_sim/engine/world/world.h"

namespace mass_aggregate_sim {
namespace engine {

struct ContactWorkspace;
struct BodyWorkspace;

// Everything the stages of a step read and write, built once per step by World::beginStep(): the
// substep h, the particles, the force scene and the force stage, the integrator's state and
// caches, the contact state, and the guards. The stages take this, not the same arguments over
// and over.
class StepContext {
 public:
  StepContext(const WorldConfig& config, const CollisionSettings& collisions,
              ParticleStore& particles, const ForceGenerators& generators, const Links& links,
              const Colliders& colliders, const ParticleMaterials& materials, ForceScene scene,
              IntegratorState& integration, StepCaches& caches, ContactWorkspace& contacts,
              GuardState& guard, ContactStats& contact_stats, std::size_t& dropped)
      : config(config),
        collisions(collisions),
        particles(particles),
        generators(generators),
        links(links),
        colliders(colliders),
        materials(materials),
        scene(scene),
        integration(integration),
        caches(caches),
        contacts(contacts),
        guard(guard),
        contact_stats(contact_stats),
        dropped(dropped) {}

  Real dt = 0.0;  // the step
  Real h = 0.0;   // the substep
  int substeps = 1;
  std::uint64_t step = 0;  // the step being taken (for divergence events)
  Real time = 0.0;         // and its start time
  const WorldConfig& config;
  const CollisionSettings& collisions;
  ParticleStore& particles;
  const ForceGenerators& generators;
  const Links& links;
  const Colliders& colliders;
  const ParticleMaterials& materials;
  ForceScene scene;
  IntegratorState& integration;
  StepCaches& caches;
  ContactWorkspace& contacts;
  GuardState& guard;
  ContactStats& contact_stats;  // of the last substep
  std::size_t& dropped;         // contacts dropped by max_contacts, over the step
  int substep = 0;              // the substep being taken
  // Rigid bodies: all null in a world without them (their stages return at once).
  BodyStore* bodies = nullptr;
  Joints* joints = nullptr;
  const BodyForceGenerators* body_generators = nullptr;
  // A generator on bodies acts on a particle: the particles feel external forces every substep.
  bool body_forces_reach_particles = false;
  const BodySettings* body_settings = nullptr;
  BodyWorkspace* body_ws = nullptr;
  // Changes whenever a collider is added or removed (the bodies' broadphase holds them).
  std::uint64_t colliders_version = 0;
  // The world has colliders, links or colliding particles: the contact stages run.
  bool contacts_active = false;
  // The energy guard judges this step.
  bool guard_energy = false;
  // The semi-implicit Euler pass sums the guard's energies (nothing moves the particles after it).
  bool pass_sums_energies = false;
  // Or, when the guard does not judge the step, probes the state it writes for the divergence
  // check (allFinite()) instead of a pass of its own after the step.
  bool pass_probes_finite = false;

  // The force stage: accelerations at (x, v) for this substep (external forces unless told).
  void accelerations(const Eigen::Ref<const Vec3Array>& x, const Eigen::Ref<const Vec3Array>& v,
                     Eigen::Ref<Vec3Array> out, const bool external = true) {
    caches.forces.accelerations(scene, x, v, h, out, external);
  }
  void externalAccelerations(Vec3Array& out) const {
    ForceStage::externalAccelerations(scene, out);
  }
  // Records a divergence found during the step.
  void reportDivergence(const ParticleId particle, const std::string& what) {
    guard.last_divergence = DivergenceEvent{step, time, particle, BodyId{}, what};
    ++guard.divergence_count;
  }
  void reportBodyDivergence(const BodyId body, const std::string& what) {
    guard.last_divergence = DivergenceEvent{step, time, ParticleId{}, body, what};
    ++guard.divergence_count;
  }
};

}  // namespace engine
}  // namespace mass_aggregate_sim
