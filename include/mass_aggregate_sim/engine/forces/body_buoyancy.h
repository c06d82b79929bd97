#pragma once

#include "mass_aggregate_sim/engine/forces/body_force_kind.h"

namespace mass_aggregate_sim {
namespace engine {

// Buoyancy (buoyancy.h) of a body, at its centre of mass: with s = up.c - surface_height the
// centre's height above the surface, F = rho V |g| f(s) up, f the submerged fraction (1 below
// -max_depth, 0 above max_depth, linear between). V <= 0 takes the volume of the body's shapes
// when it is added; a negative max_depth takes the body's reach along up (its bounding radius).
// Acting at the centre of mass it floats a body at the right depth but does not right it.
struct BodyBuoyancy {
  BodyId body;
  Real max_depth = -1.0;  // m
  Real volume = 0.0;      // m^3
  Real liquid_density = 1000.0;
  Real surface_height = 0.0;
  Vec3 up = Vec3::UnitZ();  // normalised when added
  GeneratorId id = 0;
};

template <>
struct BodyForceKind<BodyBuoyancy> {
  static constexpr const char* kName = "body buoyancy";
  static Status validate(BodyBuoyancy& buoyancy, const JointScene& scene);
  static std::vector<BodyId> bodiesOf(const BodyBuoyancy& buoyancy) { return {buoyancy.body}; }
  static bool refersTo(const BodyBuoyancy& buoyancy, BodyId id) { return buoyancy.body == id; }
  static bool refersTo(const BodyBuoyancy& buoyancy, ParticleId id) { return false; }
  static bool joins(const BodyBuoyancy& buoyancy) { return false; }
  static bool reachesParticle(const BodyBuoyancy& buoyancy) { return false; }
  static void accumulate(const std::vector<BodyBuoyancy>& buoyancies, const BodyForceScene& scene,
                         BodyForceSums& sums);
  static void stiffness(const std::vector<BodyBuoyancy>& buoyancies, const BodyForceScene& scene,
                        std::vector<BodyStiffnessTerm>& terms) {}
  static Real energy(const std::vector<BodyBuoyancy>& buoyancies, const BodyForceScene& scene) {
    return 0.0;
  }
};

}  // namespace engine
}  // namespace mass_aggregate_sim
