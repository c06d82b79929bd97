#pragma once

#include "mass_aggregate_sim/engine/forces/force_kind.h"

namespace mass_aggregate_sim {
namespace engine {

// Buoyancy of a particle against a liquid whose surface is the plane up.x = surface_height.
// With s = up.x - surface_height the particle's height above the surface:
//   s >= max_depth: out of the liquid, no force;  s <= -max_depth: fully submerged, rho V |g| up;
//   in between, linear: rho V |g| (max_depth - s) / (2 max_depth) up.
struct Buoyancy {
  ParticleId particle;
  Real max_depth = 0.1;
  Real volume = 0.0;
  Real liquid_density = 1000.0;
  Real surface_height = 0.0;
  Vec3 up = Vec3::UnitZ();  // normalised when added
  GeneratorId id = 0;
};

template <>
struct ForceKind<Buoyancy> {
  static constexpr const char* kName = "buoyancy";
  // Its force depends on height in a way the guard's potential energy leaves out.
  static constexpr bool kDrawn = false;
  static constexpr bool kUncountedWork = true;
  static Status validate(Buoyancy& buoyancy, const ParticleStore& particles);
  static bool refersTo(const Buoyancy& buoyancy, ParticleId id) { return buoyancy.particle == id; }
  static void accumulate(const std::vector<Buoyancy>& buoyancies, const ForceEvaluation& e,
                         Eigen::Ref<Vec3Array> force, Real* elastic);
  static Real energy(const std::vector<Buoyancy>& buoyancies, const ForceEvaluation& e) {
    return 0.0;
  }
  static void linearise(const std::vector<Buoyancy>& buoyancies, ImplicitSystem& system);
  static void stiffness(const std::vector<Buoyancy>& buoyancies, const ParticleStore& particles,
                        std::vector<StiffnessTerm>& terms) {}
  static void decay(const std::vector<Buoyancy>& buoyancies, const ParticleStore& particles,
                    std::vector<DecayTerm>& terms) {}
};

}  // namespace engine
}  // namespace mass_aggregate_sim
