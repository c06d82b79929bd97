#pragma once

#include "mass_aggregate_sim/engine/forces/force_kind.h"

namespace mass_aggregate_sim {
namespace engine {

// F = -(k1 |v| + k2 |v|^2) v/|v|
struct Drag {
  ParticleId particle;
  Real k1 = 0.0;  // N s/m
  Real k2 = 0.0;  // N s^2/m^2
  GeneratorId id = 0;
};

template <>
struct ForceKind<Drag> {
  static constexpr const char* kName = "drag";
  static constexpr bool kDrawn = false;
  static constexpr bool kUncountedWork = false;
  static Status validate(Drag& drag, const ParticleStore& particles);
  static bool refersTo(const Drag& drag, ParticleId id) { return drag.particle == id; }
  static void accumulate(const std::vector<Drag>& drags, const ForceEvaluation& e,
                         Eigen::Ref<Vec3Array> force, Real* elastic);
  static Real energy(const std::vector<Drag>& drags, const ForceEvaluation& e) { return 0.0; }
  static void linearise(const std::vector<Drag>& drags, ImplicitSystem& system);
  static void stiffness(const std::vector<Drag>& drags, const ParticleStore& particles,
                        std::vector<StiffnessTerm>& terms) {}
  static void decay(const std::vector<Drag>& drags, const ParticleStore& particles,
                    std::vector<DecayTerm>& terms);
};

}  // namespace engine
}  // namespace mass_aggregate_sim
