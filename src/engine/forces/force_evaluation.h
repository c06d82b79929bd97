#pragma once
// The force stage's view of the force generators: every kind of ForceKinds evaluated through its
// ForceKind<K> traits, in the list's order.

#include <cstddef>
#include <vector>

#include "engine/forces/spring_runs.h"
#include "mass_aggregate_sim/engine/core/particle_store.h"
#include "mass_aggregate_sim/engine/core/types.h"
#include "mass_aggregate_sim/engine/forces/force_generators.h"

namespace mass_aggregate_sim {
namespace engine {

// What a force kind reads to evaluate its forces: positions x and velocities v (dense order,
// the store's size; the integrators' stages pass their own), the magnitude of gravity (buoyancy),
// the substep the stiff springs move over, and the springs' dense layout.
struct ForceEvaluation {
  const ParticleStore& particles;
  const Eigen::Ref<const Vec3Array>& x;
  const Eigen::Ref<const Vec3Array>& v;
  Real gravity_magnitude;
  Real dt;
  const DenseSprings& springs;
};

// One spring for the stability analysis: its ends (dense; b = kAnchorEnd for an anchor),
// stiffness and damping.
struct StiffnessTerm {
  static constexpr std::size_t kAnchorEnd = static_cast<std::size_t>(-1);
  GeneratorId id = 0;
  std::size_t a = 0;
  std::size_t b = kAnchorEnd;
  Real stiffness = 0.0;
  Real damping = 0.0;  // c along the spring, N s/m
};

// Adds the force of every generator at (e.x, e.v) to `force`, kind by kind; with `elastic`,
// also their elastic energy at e.x (the springs' from the lengths the force pass computes).
// A pure function of its arguments, so RK4 can call it per stage.
void accumulateGeneratorForces(const ForceGenerators& generators, const ForceEvaluation& e,
                               Eigen::Ref<Vec3Array> force, Real* elastic = nullptr);
// Elastic energy stored in the generators at e.x.
Real generatorPotentialEnergy(const ForceGenerators& generators, const ForceEvaluation& e);
// Whether some generator does work the energy guard cannot count (ForceKind::kUncountedWork).
bool generatorsDoUncountedWork(const ForceGenerators& generators);
// Every spring that limits the step, for the stability analysis.
std::vector<StiffnessTerm> stiffnessTerms(const ForceGenerators& generators,
                                          const ParticleStore& particles);

}  // namespace engine
}  // namespace mass_aggregate_sim
