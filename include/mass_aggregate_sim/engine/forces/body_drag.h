#pragma once

#include "mass_aggregate_sim/engine/forces/body_force_kind.h"

namespace mass_aggregate_sim {
namespace engine {

// Drag (drag.h) on a body's centre of mass, F = -(k1 + k2 |v|) v, and a turning drag about it,
// T = -angular w. Body damping (BodySpec) is the same linear law integrated implicitly; this is
// the generator a scene adds, removes and tunes like a particle's drag.
struct BodyDrag {
  BodyId body;
  Real k1 = 0.0;       // N s/m
  Real k2 = 0.0;       // N s^2/m^2
  Real angular = 0.0;  // N m s
  GeneratorId id = 0;
};

template <>
struct BodyForceKind<BodyDrag> {
  static constexpr const char* kName = "body drag";
  static Status validate(BodyDrag& drag, const JointScene& scene);
  static std::vector<BodyId> bodiesOf(const BodyDrag& drag) { return {drag.body}; }
  static bool refersTo(const BodyDrag& drag, BodyId id) { return drag.body == id; }
  static bool refersTo(const BodyDrag& drag, ParticleId id) { return false; }
  static bool joins(const BodyDrag& drag) { return false; }
  static bool reachesParticle(const BodyDrag& drag) { return false; }
  static void accumulate(const std::vector<BodyDrag>& drags, const BodyForceScene& scene,
                         BodyForceSums& sums);
  static void stiffness(const std::vector<BodyDrag>& drags, const BodyForceScene& scene,
                        std::vector<BodyStiffnessTerm>& terms) {}
  static void decay(const std::vector<BodyDrag>& drags, const BodyForceScene& scene,
                    std::vector<DecayTerm>& terms);
  static Real energy(const std::vector<BodyDrag>& drags, const BodyForceScene& scene) {
    return 0.0;
  }
};

}  // namespace engine
}  // namespace mass_aggregate_sim
