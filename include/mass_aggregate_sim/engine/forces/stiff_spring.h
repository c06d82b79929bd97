#pragma once

#include "mass_aggregate_sim/engine/forces/force_kind.h"

namespace mass_aggregate_sim {
namespace engine {

// A spring from a particle to a fixed anchor, too stiff to integrate, moved in closed form: each
// substep the particle follows the exact damped harmonic motion about its equilibrium (see
// stiffSpringStage()), position and velocity, at any stiffness and under every integrator.
struct StiffSpring {
  ParticleId particle;
  Vec3 anchor = Vec3::Zero();
  Real stiffness = 0.0;  // k, N/m
  Real damping = 0.0;    // c, N s/m
  GeneratorId id = 0;
};

template <>
struct ForceKind<StiffSpring> {
  static constexpr const char* kName = "stiff_spring";
  static constexpr bool kUncountedWork = false;
  static constexpr bool kDrawn = true;
  // Tension k l (rest length 0).
  static DrawnSegment drawn(const StiffSpring& spring, const ParticleStore& particles);
  static Status validate(StiffSpring& spring, const ParticleStore& particles);
  static bool refersTo(const StiffSpring& spring, ParticleId id) { return spring.particle == id; }
  // The integrators see the spring as the constant acceleration that carries the particle from
  // (x, v) to where its exact motion puts it after e.dt (x + v dt + a dt^2 lands there), so what
  // its neighbours feel during the substep follows it.
  static void accumulate(const std::vector<StiffSpring>& springs, const ForceEvaluation& e,
                         Eigen::Ref<Vec3Array> force, Real* elastic);
  static Real energy(const std::vector<StiffSpring>& springs, const ForceEvaluation& e);
  // Moved in closed form, not linearised.
  static void linearise(const std::vector<StiffSpring>& springs, ImplicitSystem& system) {}
  // Never limits the step.
  static void stiffness(const std::vector<StiffSpring>& springs, const ParticleStore& particles,
                        std::vector<StiffnessTerm>& terms) {}
  static void decay(const std::vector<StiffSpring>& springs, const ParticleStore& particles,
                    std::vector<DecayTerm>& terms) {}
};

}  // namespace engine
}  // namespace mass_aggregate_sim
