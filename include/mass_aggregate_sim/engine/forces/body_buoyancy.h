#pragma once

#include "mass_aggregate_sim/engine/forces/body_force_kind.h"

namespace mass_aggregate_sim {
namespace engine {

// How a body's buoyancy finds the liquid it displaces.
enum class BuoyancyModel {
  // The part of each of its shapes below the surface, exact (BodyShapeKind::submerged), pushed
  // up at its centroid, the centre of buoyancy: F = rho |g| V_sub up at c_sub. Off the line
  // through the centre of mass it turns the body: a floating plank rights itself, a log of half
  // the liquid's density rolls onto an edge. A volume given (> 0) scales the shapes' part so that
  // the whole body displaces that much.
  kShapes,
  // The particles' law (buoyancy.h) at the centre of mass: with s = up.c - surface_height,
  // F = rho V |g| f(s) up, f the submerged fraction (1 below -max_depth, 0 above max_depth,
  // linear between). It floats a body at a depth but never turns it.
  kCentre,
};

// Buoyancy of a body in a liquid filling the half-space below surface_height along up. V <= 0
// takes the volume of the body's shapes when it is added; for kCentre a negative max_depth takes
// the body's reach (its bounding radius), and kShapes takes no max_depth.
struct BodyBuoyancy {
  BodyId body;
  BuoyancyModel model = BuoyancyModel::kShapes;
  Real max_depth = -1.0;  // m (kCentre)
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
  static void decay(const std::vector<BodyBuoyancy>& buoyancies, const BodyForceScene& scene,
                    std::vector<DecayTerm>& terms) {}
  static Real energy(const std::vector<BodyBuoyancy>& buoyancies, const BodyForceScene& scene) {
    return 0.0;
  }
};

}  // namespace engine
}  // namespace mass_aggregate_sim
