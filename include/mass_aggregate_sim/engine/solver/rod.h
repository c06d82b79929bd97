#pragma once

#include "mass_aggregate_sim/engine/solver/link_kind.h"

namespace mass_aggregate_sim {
namespace engine {

// Keeps two particles (or a particle and an anchor, b invalid) exactly length apart, within
// CollisionSettings::rod_tolerance (relative).
struct Rod {
  ParticleId a;
  ParticleId b;                // invalid: anchored at `anchor`
  Vec3 anchor = Vec3::Zero();  // the fixed end of an anchored rod
  Real length = 1.0;
  GeneratorId id = 0;

  bool anchored() const { return !b.valid(); }
  static Rod between(const ParticleId a, const ParticleId b, const Real length) {
    Rod r;
    r.a = a;
    r.b = b;
    r.length = length;
    return r;
  }
  static Rod anchoredAt(const ParticleId a, const Vec3& anchor, const Real length) {
    Rod r;
    r.a = a;
    r.anchor = anchor;
    r.length = length;
    return r;
  }
};

template <>
struct LinkKind<Rod> {
  static constexpr const char* kName = "rod";
  static Status validate(Rod& rod, const ParticleStore& particles);
  static bool refersTo(const Rod& rod, ParticleId id) { return rod.a == id || rod.b == id; }
  static LinkLimits limits(const Rod& rod) { return LinkLimits{rod.length, false, 0.0}; }
};

}  // namespace engine
}  // namespace mass_aggregate_sim
