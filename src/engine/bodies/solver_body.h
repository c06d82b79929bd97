#pragma once
// What the body solver works on during a step: per moving body (awake dynamic or kinematic bodies,
// and particles that touch bodies) its velocities, how far it has moved and turned since the step
// began, and its inverse mass and world inverse inertia (fixed for the step). A side that never
// moves (a fixed body, a static collider, a sleeping body) is kNoBody and reads as at rest.

#include <cstdint>

#include "mass_aggregate_sim/engine/core/transform.h"

namespace mass_aggregate_sim {
namespace engine {

struct SolverBody {
  Vec3 v = Vec3::Zero();
  Vec3 w = Vec3::Zero();
  // Pseudo-velocities of the substep (split impulses): they push overlap out, move the positions
  // with the velocities, and are then dropped.
  Vec3 pv = Vec3::Zero();
  Vec3 pw = Vec3::Zero();
  Vec3 dp = Vec3::Zero();             // position change since the step began
  Quat dq = Quat::Identity();         // rotation since the step began: q = dq q0
  Mat3 dq_matrix = Mat3::Identity();  // dq as a matrix, kept with it
  Real inverse_mass = 0.0;
  Mat3 inverse_inertia = Mat3::Zero();  // world frame (zero for a particle)
  // The acceleration of the substep (gravity and forces), and whether a contact, a joint or a
  // force generator holds the body this step: a free body's position follows it exactly (a
  // parabola), a held one moves with the velocity the solver leaves (semi-implicit Euler).
  Vec3 acceleration = Vec3::Zero();
  bool held = false;
  // An impact of this substep has moved the body as a free body would have flown (-a h^2 / 2).
  bool flew = false;

  Vec3 velocityAt(const Vec3& r) const { return v + w.cross(r); }
  // An impulse p at r from the centre of mass: v += p / m, w += I^-1 (r x p).
  void applyImpulse(const Vec3& r, const Vec3& p) {
    v += inverse_mass * p;
    w += inverse_inertia * r.cross(p);
  }
  Vec3 pseudoVelocityAt(const Vec3& r) const { return pv + pw.cross(r); }
  void applyPseudoImpulse(const Vec3& r, const Vec3& p) {
    pv += inverse_mass * p;
    pw += inverse_inertia * r.cross(p);
  }
};

// The solver body index of a side that never moves.
constexpr std::int32_t kNoBody = -1;

// The effective mass of an impulse along direction n at r_a on a and r_b on b:
//   1 / (w_a + w_b + (r_a x n).I_a^-1 (r_a x n) + (r_b x n).I_b^-1 (r_b x n)), 0 when nothing
//   moves.
inline Real effectiveMass(const SolverBody& a, const Vec3& r_a, const SolverBody& b,
                          const Vec3& r_b, const Vec3& n) {
  const Vec3 ra_n = r_a.cross(n);
  const Vec3 rb_n = r_b.cross(n);
  const Real k = a.inverse_mass + b.inverse_mass + ra_n.dot(a.inverse_inertia * ra_n) +
                 rb_n.dot(b.inverse_inertia * rb_n);
  return k > 0.0 ? 1.0 / k : 0.0;
}

}  // namespace engine
}  // namespace mass_aggregate_sim
