#pragma once
// The force stage of the generators on bodies (body_force_kind.h): where each end of a generator
// is and how fast it moves (at the start of the substep while a step runs, as stored between
// steps), where the forces go, and the stage itself.

#include <cstdint>
#include <vector>

#include "engine/bodies/solver_body.h"
#include "mass_aggregate_sim/engine/bodies/body_store.h"
#include "mass_aggregate_sim/engine/core/particle_store.h"
#include "mass_aggregate_sim/engine/forces/body_force_generators.h"

namespace mass_aggregate_sim {
namespace engine {

struct BodyWorkspace;
class StepContext;

// One end of a generator: a point of a body, a particle, or a point in the world.
struct ForceEnd {
  Vec3 position = Vec3::Zero();
  Vec3 velocity = Vec3::Zero();
  Vec3 r = Vec3::Zero();          // from the body's centre of mass
  std::int32_t solver = kNoBody;  // the solver body a body end's force goes to
  std::int64_t particle = -1;     // the dense index of a particle end
};

// A spring between generator ends as the stability analysis sees it (stability.h): its stiffness
// and, per end, the most inverse mass the end shows along any line (BodyForceScene::mobility).
struct BodyStiffnessTerm {
  GeneratorId id = 0;
  Real stiffness = 0.0;
  Real damping = 0.0;  // c along the spring, N s/m
  Real mobility[2] = {0.0, 0.0};
  std::int64_t particle[2] = {-1, -1};  // the dense index of a particle end
};

class BodyForceScene {
 public:
  // With `ws`, the bodies as the step has moved them so far (its solver bodies); without, as
  // stored.
  BodyForceScene(const BodyStore& bodies, const ParticleStore& particles, const BodyWorkspace* ws,
                 Real gravity_magnitude)
      : bodies_(bodies), particles_(particles), ws_(ws), gravity_magnitude_(gravity_magnitude) {}

  ForceEnd end(const JointEnd& end) const;
  // The largest 1/m_eff a force along any line n at the end meets: 1/m + (r x n).I^-1 (r x n),
  // at most 1/m + |r|^2 / I_min for a point r from a body's centre of mass (whatever the body's
  // turn); 1/m for a particle; 0 for the world or a body that never moves.
  Real mobility(const JointEnd& end) const;
  // A body's centre of mass, as an end.
  ForceEnd centre(BodyId body) const;
  // A body's mass frame (centre of mass, principal axes) as the step has moved it so far.
  Transform massPose(BodyId body) const;
  Vec3 angularVelocity(BodyId body) const;
  const BodyStore& bodies() const { return bodies_; }
  Real gravityMagnitude() const { return gravity_magnitude_; }

 private:
  const SolverBody* solverBody(std::size_t dense) const;

  const BodyStore& bodies_;
  const ParticleStore& particles_;
  const BodyWorkspace* ws_;
  Real gravity_magnitude_;
};

// Where the generators' forces go: each moving body's force and torque about its centre of mass
// (by solver body), each particle's force (by dense index; none when no generator reaches one).
class BodyForceSums {
 public:
  BodyForceSums(std::vector<Vec3>& force, std::vector<Vec3>& torque, Vec3Array* particle_force)
      : force_(force), torque_(torque), particle_force_(particle_force) {}
  // F at the end: a body feels F and r x F, a particle F, the world nothing.
  void add(const ForceEnd& end, const Vec3& f);
  void addTorque(const ForceEnd& end, const Vec3& torque);

 private:
  std::vector<Vec3>& force_;
  std::vector<Vec3>& torque_;
  Vec3Array* particle_force_;
};

// Whether a generator acts on a particle (then the particles feel external forces every step).
bool bodyForcesReachParticles(const BodyForceGenerators& generators);
// Their elastic energy at the stored state.
Real bodyGeneratorEnergy(const BodyForceGenerators& generators, const BodyStore& bodies,
                         const ParticleStore& particles);
// The bodies that stay awake because a generator joins them to something else that moves.
void markJoinedBodies(const BodyForceGenerators& generators, const BodyStore& bodies,
                      std::vector<std::uint8_t>& busy);

// The stage, at the start of each substep: every generator's force at the state the substep
// starts from, into the solver bodies' sums (read by the bodies' velocity stage) and into the
// particles' external forces (the user's forces of the step plus these).
void applyBodyForces(StepContext& ctx);

}  // namespace engine
}  // namespace mass_aggregate_sim
