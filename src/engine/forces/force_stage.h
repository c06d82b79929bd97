#pragma once

#include <cstdint>

#include "engine/forces/force_evaluation.h"
#include "engine/forces/spring_runs.h"
#include "mass_aggregate_sim/engine/core/particle_store.h"
#include "mass_aggregate_sim/engine/forces/force_generators.h"

namespace mass_aggregate_sim {
namespace engine {

// What the force stage acts on: the particles, their generators, gravity and whether external
// forces (addForce) are set this step. generators_version changes whenever a generator is added
// or removed.
struct ForceScene {
  const ParticleStore& particles;
  const ForceGenerators& generators;
  std::uint64_t generators_version;
  Vec3 gravity;
  bool external;
};

// The force stage: every force on every particle, as accelerations. It is the only place forces
// are evaluated; every integrator calls it (RK4 once per stage). Its caches are optimisations
// inside it, never a second path: the springs' dense layout (rebuilt when the generators or the
// particles' layout change), and the generator forces the energy guard evaluated ahead at the
// state a step ended in, which the next step takes instead of evaluating them again when nothing
// changed in between (the same calls on the same state: the same bits).
class ForceStage {
 public:
  // a = (F_generators [+ F_external]) / m + g + a_own for movable particles, 0 for immovable ones,
  // at positions x and velocities v, for a substep of h (the stiff springs' horizon).
  void accelerations(const ForceScene& scene, const Eigen::Ref<const Vec3Array>& x,
                     const Eigen::Ref<const Vec3Array>& v, Real h, Eigen::Ref<Vec3Array> out,
                     bool with_external = true);
  // The generator forces alone at the store's state, with their elastic energy; kept for the next
  // step's first evaluation (takeForcesAhead).
  Real evaluateAhead(const ForceScene& scene, Real h);
  // The forces evaluateAhead() kept, when still valid for this state and no external force is
  // set: swapped into `force` (the generator forces, not yet divided by the masses).
  bool takeForcesAhead(const ForceScene& scene, Vec3Array& force);
  // The generator forces at (x, v) into `force` (not divided by the masses); with `elastic`, their
  // elastic energy.
  void generatorForces(const ForceScene& scene, const Eigen::Ref<const Vec3Array>& x,
                       const Eigen::Ref<const Vec3Array>& v, Real h, Eigen::Ref<Vec3Array> force,
                       Real* elastic = nullptr);
  // F / m of the external forces (zero when there are none).
  static void externalAccelerations(const ForceScene& scene, Vec3Array& out);
  // The generators' elastic energy at the store's positions.
  Real elasticEnergy(const ForceScene& scene);
  // Forgets the forces kept ahead (the state changed).
  void forgetAhead() { ahead_valid_ = false; }

 private:
  const DenseSprings& springs(const ForceScene& scene);

  DenseSprings springs_;
  std::uint64_t springs_layout_ = ~std::uint64_t{0};
  std::uint64_t springs_version_ = ~std::uint64_t{0};
  Vec3Array ahead_;
  bool ahead_valid_ = false;
};

class StepContext;

// The force stage's part of a substep before the integrator runs: the forces of the generators on
// bodies (body_force_stage.h), what the stiff springs' closed form needs from the start of the
// substep (stiff_spring_stage.h), and the start positions the swept tests measure from.
void applyForces(StepContext& ctx);

}  // namespace engine
}  // namespace mass_aggregate_sim
