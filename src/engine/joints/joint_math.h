#pragma once
// What the joint kinds share in a solver pass: the two sides as they are now (anchors and
// orientations turned by what the bodies turned since the step began), the point error and its
// effective mass, and impulses applied to both sides.

#include <vector>

#include "engine/bodies/joint_rows.h"
#include "engine/bodies/solver_body.h"

namespace mass_aggregate_sim {
namespace engine {

inline Mat3 skew(const Vec3& v) {
  Mat3 m;
  m << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return m;
}

class JointSides {
 public:
  JointSides(const JointRow& row, std::vector<SolverBody>& bodies)
      : row_(row),
        a_(row.a == kNoBody ? still_ : bodies[static_cast<std::size_t>(row.a)]),
        b_(row.b == kNoBody ? still_b_ : bodies[static_cast<std::size_t>(row.b)]),
        r_a(a_.dq * row.r_a),
        r_b(b_.dq * row.r_b),
        q_a((a_.dq * row.q_a).normalized()),
        q_b((b_.dq * row.q_b).normalized()) {}

  // C = p_b - p_a: where anchor b is now less where anchor a is.
  Vec3 pointError() const { return (row_.center_b + b_.dp + r_b) - (row_.center_a + a_.dp + r_a); }
  // dC/dt = v_b + w_b x r_b - v_a - w_a x r_a.
  Vec3 pointVelocity() const { return b_.velocityAt(r_b) - a_.velocityAt(r_a); }
  // K = (m_a + m_b) E - [r_a] I_a^-1 [r_a] - [r_b] I_b^-1 [r_b]: the point's effective mass^-1.
  Mat3 pointMass() const {
    const Mat3 ra = skew(r_a);
    const Mat3 rb = skew(r_b);
    return (a_.inverse_mass + b_.inverse_mass) * Mat3::Identity() - ra * a_.inverse_inertia * ra -
           rb * b_.inverse_inertia * rb;
  }
  Vec3 relativeAngularVelocity() const { return b_.w - a_.w; }
  // I_a^-1 + I_b^-1: the effective mass^-1 of an angular row.
  Mat3 angularMass() const { return a_.inverse_inertia + b_.inverse_inertia; }
  // p on b at its anchor, -p on a at its anchor.
  void applyLinear(const Vec3& p) {
    a_.applyImpulse(r_a, -p);
    b_.applyImpulse(r_b, p);
  }
  // An angular impulse L on b, -L on a.
  void applyAngular(const Vec3& l) {
    a_.w -= a_.inverse_inertia * l;
    b_.w += b_.inverse_inertia * l;
  }

 private:
  const JointRow& row_;
  SolverBody still_;
  SolverBody still_b_;
  SolverBody& a_;
  SolverBody& b_;

 public:
  const Vec3 r_a;
  const Vec3 r_b;
  const Quat q_a;  // the sides' mass frames now
  const Quat q_b;
};

// The bias and the scales of a row in this pass: soft with the bias (solve), rigid without
// (relax).
struct RowScale {
  Real bias_rate = 0.0;
  Real mass_scale = 1.0;
  Real impulse_scale = 0.0;
};
inline RowScale rowScale(const Softness& softness, const bool use_bias) {
  if (!use_bias) return RowScale{};
  return RowScale{softness.bias_rate, softness.mass_scale, softness.impulse_scale};
}

// Solves K x = y for a 3x3 K that may be singular (a side without inertia along some direction):
// the pseudo-inverse's answer, so no row blows up.
inline Vec3 solveMass(const Mat3& k, const Vec3& y) {
  return k.completeOrthogonalDecomposition().solve(y);
}

}  // namespace engine
}  // namespace mass_aggregate_sim
