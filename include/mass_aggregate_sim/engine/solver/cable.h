#pragma once

#include "mass_aggregate_sim/engine/solver/link_kind.h"

namespace mass_aggregate_sim {
namespace engine {

// Keeps two particles (or a particle and an anchor, b invalid) at most max_length apart; when it
// snaps taut the separating speed is reflected with the given restitution.
struct Cable {
  ParticleId a;
  ParticleId b;                // invalid: anchored at `anchor`
  Vec3 anchor = Vec3::Zero();  // the fixed end of an anchored cable
  Real max_length = 1.0;
  Real restitution = 0.0;
  GeneratorId id = 0;

  bool anchored() const { return !b.valid(); }
  static Cable between(const ParticleId a, const ParticleId b, const Real max_length,
                       const Real restitution = 0.0) {
    Cable c;
    c.a = a;
    c.b = b;
    c.max_length = max_length;
    c.restitution = restitution;
    return c;
  }
  static Cable anchoredAt(const ParticleId a, const Vec3& anchor, const Real max_length,
                          const Real restitution = 0.0) {
    Cable c;
    c.a = a;
    c.anchor = anchor;
    c.max_length = max_length;
    c.restitution = restitution;
    return c;
  }
};

template <>
struct LinkKind<Cable> {
  static constexpr const char* kName = "cable";
  static Status validate(Cable& cable, const ParticleStore& particles);
  static bool refersTo(const Cable& cable, ParticleId id) { return cable.a == id || cable.b == id; }
  static LinkLimits limits(const Cable& cable) {
    return LinkLimits{cable.max_length, true, cable.restitution};
  }
};

}  // namespace engine
}  // namespace mass_aggregate_sim
