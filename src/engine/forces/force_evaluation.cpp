#include "engine/forces/force_evaluation.h"

namespace mass_aggregate_sim {
namespace engine {

void accumulateGeneratorForces(const ForceGenerators& generators, const ForceEvaluation& e,
                               Eigen::Ref<Vec3Array> force, Real* elastic) {
  generators.forEach([&](const auto& kind) {
    using Kind = typename std::decay_t<decltype(kind)>::value_type;
    if (!kind.empty()) ForceKind<Kind>::accumulate(kind, e, force, elastic);
  });
}

Real generatorPotentialEnergy(const ForceGenerators& generators, const ForceEvaluation& e) {
  Real energy = 0.0;
  generators.forEach([&](const auto& kind) {
    using Kind = typename std::decay_t<decltype(kind)>::value_type;
    if (!kind.empty()) energy += ForceKind<Kind>::energy(kind, e);
  });
  return energy;
}

bool generatorsDoUncountedWork(const ForceGenerators& generators) {
  bool uncounted = false;
  generators.forEach([&](const auto& kind) {
    using Kind = typename std::decay_t<decltype(kind)>::value_type;
    uncounted = uncounted || (ForceKind<Kind>::kUncountedWork && !kind.empty());
  });
  return uncounted;
}

std::vector<StiffnessTerm> stiffnessTerms(const ForceGenerators& generators,
                                          const ParticleStore& particles) {
  std::vector<StiffnessTerm> terms;
  generators.forEach([&](const auto& kind) {
    using Kind = typename std::decay_t<decltype(kind)>::value_type;
    ForceKind<Kind>::stiffness(kind, particles, terms);
  });
  return terms;
}

}  // namespace engine
}  // namespace mass_aggregate_sim
