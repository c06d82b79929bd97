#pragma once

#include "mass_aggregate_sim/engine/forces/body_force_kind.h"

namespace mass_aggregate_sim {
namespace engine {

// The spring (spring.h) between points that are not both particles: a point on a body (in the
// body's frame), a particle, or a fixed point in the world, at least one end on a body. With
// d = p_a - p_b, l = |d|, n = d / l and the points' velocities u_a, u_b (u = v + w x r on a body):
//   F_a = -(k (l - L) + c (u_a - u_b).n) n = -F_b,
// applied at the points (a body feels r x F about its centre of mass). pull_only makes it a
// bungee. A negative rest_length is the distance when it is added.
struct PointSpring {
  JointEnd a;
  JointEnd b;
  Real stiffness = 0.0;     // k, N/m
  Real rest_length = -1.0;  // L, m
  Real damping = 0.0;       // c, N s/m
  bool pull_only = false;
  GeneratorId id = 0;

  static PointSpring between(const JointEnd& a, const JointEnd& b, const Real stiffness,
                             const Real rest_length = -1.0, const Real damping = 0.0) {
    PointSpring s;
    s.a = a;
    s.b = b;
    s.stiffness = stiffness;
    s.rest_length = rest_length;
    s.damping = damping;
    return s;
  }
  // The same spring pulling only (a bungee).
  PointSpring pullingOnly() const {
    PointSpring s = *this;
    s.pull_only = true;
    return s;
  }
};

template <>
struct BodyForceKind<PointSpring> {
  static constexpr const char* kName = "point spring";
  static Status validate(PointSpring& spring, const JointScene& scene);
  static std::vector<BodyId> bodiesOf(const PointSpring& spring);
  static bool refersTo(const PointSpring& spring, BodyId id) {
    return spring.a.body == id || spring.b.body == id;
  }
  static bool refersTo(const PointSpring& spring, ParticleId id) {
    return spring.a.particle == id || spring.b.particle == id;
  }
  static bool joins(const PointSpring& spring) {
    return !spring.a.isWorld() && !spring.b.isWorld();
  }
  static bool reachesParticle(const PointSpring& spring) {
    return spring.a.isParticle() || spring.b.isParticle();
  }
  static void accumulate(const std::vector<PointSpring>& springs, const BodyForceScene& scene,
                         BodyForceSums& sums);
  static Real energy(const std::vector<PointSpring>& springs, const BodyForceScene& scene);
  static void stiffness(const std::vector<PointSpring>& springs, const BodyForceScene& scene,
                        std::vector<BodyStiffnessTerm>& terms);
  static void decay(const std::vector<PointSpring>& springs, const BodyForceScene& scene,
                    std::vector<DecayTerm>& terms) {}
  // The line between its ends as stored and its tension k (l - L) (0 for a slack bungee).
  static DrawnSegment drawn(const PointSpring& spring, const BodyStore& bodies,
                            const ParticleStore& particles);
};

}  // namespace engine
}  // namespace mass_aggregate_sim
