#pragma once

#include "mass_aggregate_sim/engine/forces/force_kind.h"

namespace mass_aggregate_sim {
namespace engine {

// Hooke's law between two particles, or between a particle and a fixed anchor (b invalid), signed:
// pulls when stretched, pushes when compressed, with an optional dashpot along the spring:
//   F_a = -(k (l - L) + c (v_a - v_b).n) n,  d = x_a - x_b, l = |d|, n = d / l
// (an anchor's velocity is zero). pull_only makes it a bungee: no force while l <= L.
struct Spring {
  ParticleId a;
  ParticleId b;                // invalid: anchored at `anchor`
  Vec3 anchor = Vec3::Zero();  // the fixed end of an anchored spring
  Real stiffness = 0.0;        // k, N/m
  Real rest_length = 0.0;      // L, m
  Real damping = 0.0;          // c, N s/m
  bool pull_only = false;
  GeneratorId id = 0;

  bool anchored() const { return !b.valid(); }

  static Spring between(const ParticleId a, const ParticleId b, const Real stiffness,
                        const Real rest_length, const Real damping = 0.0) {
    Spring s;
    s.a = a;
    s.b = b;
    s.stiffness = stiffness;
    s.rest_length = rest_length;
    s.damping = damping;
    return s;
  }
  static Spring anchoredAt(const ParticleId a, const Vec3& anchor, const Real stiffness,
                           const Real rest_length, const Real damping = 0.0) {
    Spring s;
    s.a = a;
    s.anchor = anchor;
    s.stiffness = stiffness;
    s.rest_length = rest_length;
    s.damping = damping;
    return s;
  }
  // The same spring pulling only (a bungee).
  Spring pullingOnly() const {
    Spring s = *this;
    s.pull_only = true;
    return s;
  }
};

template <>
struct ForceKind<Spring> {
  static constexpr const char* kName = "spring";
  static constexpr bool kUncountedWork = false;
  static constexpr bool kDrawn = true;
  // Tension k (l - L); zero for a slack bungee.
  static DrawnSegment drawn(const Spring& spring, const ParticleStore& particles);
  static Status validate(Spring& spring, const ParticleStore& particles);
  static bool refersTo(const Spring& spring, ParticleId id) {
    return spring.a == id || spring.b == id;
  }
  static void accumulate(const std::vector<Spring>& springs, const ForceEvaluation& e,
                         Eigen::Ref<Vec3Array> force, Real* elastic);
  static Real energy(const std::vector<Spring>& springs, const ForceEvaluation& e);
  static void linearise(const std::vector<Spring>& springs, ImplicitSystem& system);
  static void stiffness(const std::vector<Spring>& springs, const ParticleStore& particles,
                        std::vector<StiffnessTerm>& terms);
  static void decay(const std::vector<Spring>& springs, const ParticleStore& particles,
                    std::vector<DecayTerm>& terms) {}
};

}  // namespace engine
}  // namespace mass_aggregate_sim
