// The hinge joint kind (hinge_joint.h).
#include "mass_aggregate_sim/engine/joints/hinge_joint.h"

#include <algorithm>
#include <cmath>

#include "engine/bodies/contact_solver.h"
#include "engine/core/state_hash.h"
#include "engine/joints/end_frames.h"
#include "engine/joints/joint_math.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

// The mass of a row along axis u of the angular velocity difference: 1 / u.(I_a^-1 + I_b^-1) u.
Real axialMass(const JointSides& sides, const Vec3& u) {
  const Real k = u.dot(sides.angularMass() * u);
  return k > 0.0 ? 1.0 / k : 0.0;
}

// One side of a limit: C >= 0 held by an impulse >= 0 along `direction` (+axis for the lower
// limit, -axis for the upper). A limit not yet reached is speculative: it may close within h.
void solveLimit(JointSides& sides, const Vec3& direction, const Real c, Real& total,
                const Softness& softness, const JointPass& pass) {
  Real bias = 0.0;
  Real mass_scale = 1.0;
  Real impulse_scale = 0.0;
  if (c > 0.0) {
    bias = c / pass.h;
  } else if (pass.use_bias) {
    bias = softness.bias_rate * c;
    mass_scale = softness.mass_scale;
    impulse_scale = softness.impulse_scale;
  }
  const Real c_dot = direction.dot(sides.relativeAngularVelocity());
  const Real impulse =
      -axialMass(sides, direction) * mass_scale * (c_dot + bias) - impulse_scale * total;
  const Real updated = std::max(total + impulse, 0.0);
  sides.applyAngular((updated - total) * direction);
  total = updated;
}

}  // namespace

Status JointKind<HingeJoint>::validate(HingeJoint& joint, const JointScene& scene) {
  if (!joint.axis.allFinite() || joint.axis.norm() < 1e-9) {
    return Status::error("hinge axis must be finite and of non-zero length");
  }
  if (!std::isfinite(joint.lower) || !std::isfinite(joint.upper) || joint.lower < -M_PI ||
      joint.upper > M_PI || joint.lower > joint.upper) {
    return Status::error("hinge limits must satisfy -pi <= lower <= upper <= pi");
  }
  if (!std::isfinite(joint.motor_speed)) return Status::error("hinge motor_speed is not finite");
  if (!std::isfinite(joint.max_motor_torque) || joint.max_motor_torque < 0.0) {
    return Status::error("hinge max_motor_torque must be finite and >= 0");
  }
  joint.axis.normalize();
  const Quat q_a = endOrientation(joint.a, scene.bodies);
  const Quat q_b = endOrientation(joint.b, scene.bodies);
  joint.axis_a = q_a.conjugate() * joint.axis;
  joint.axis_b = q_b.conjugate() * joint.axis;
  joint.reference = q_a.conjugate() * q_b;
  joint.linear_impulse.setZero();
  joint.angular_impulse.setZero();
  joint.lower_impulse = joint.upper_impulse = joint.motor_impulse = 0.0;
  return Status::ok();
}

Real JointKind<HingeJoint>::angle(const HingeJoint& joint, const Quat& q_a, const Quat& q_b) {
  // b's turn relative to a since the joint was added, in a's frame: (q_a^-1 q_b) reference^-1.
  const Quat turn = q_a.conjugate() * q_b * joint.reference.conjugate();
  const Real angle = 2.0 * std::atan2(turn.vec().dot(joint.axis_a), turn.w());
  return angle > M_PI ? angle - 2.0 * M_PI : (angle <= -M_PI ? angle + 2.0 * M_PI : angle);
}

void JointKind<HingeJoint>::warmStart(const HingeJoint& joint, const JointRow& row,
                                      std::vector<SolverBody>& bodies) {
  JointSides sides(row, bodies);
  const Vec3 axis = sides.q_a * joint.axis_a;
  sides.applyLinear(joint.linear_impulse);
  sides.applyAngular(joint.angular_impulse +
                     (joint.motor_impulse + joint.lower_impulse - joint.upper_impulse) * axis);
}

void JointKind<HingeJoint>::solve(HingeJoint& joint, const JointRow& row, const JointPass& pass) {
  JointSides sides(row, pass.bodies);
  const Vec3 axis = sides.q_a * joint.axis_a;
  if (joint.motor) {
    // Drives the relative speed about the axis to motor_speed, with at most the torque given.
    const Real c_dot = axis.dot(sides.relativeAngularVelocity()) - joint.motor_speed;
    const Real most = joint.max_motor_torque * pass.h;
    const Real updated =
        std::clamp(joint.motor_impulse - axialMass(sides, axis) * c_dot, -most, most);
    sides.applyAngular((updated - joint.motor_impulse) * axis);
    joint.motor_impulse = updated;
  }
  if (joint.limit) {
    const Real theta = angle(joint, sides.q_a, sides.q_b);
    solveLimit(sides, axis, theta - joint.lower, joint.lower_impulse, row.softness, pass);
    solveLimit(sides, -axis, joint.upper - theta, joint.upper_impulse, row.softness, pass);
  }
  joint.world_axis = axis;
  {
    // b's axis kept along a's: two rows about the directions p perpendicular to a's axis, with
    // C_p = p.(axis_a x axis_b) (the small turn about p) and dC_p/dt = p.(w_b - w_a).
    Vec3 p[2];
    tangentBasis(axis, p[0], p[1]);
    const Vec3 error = axis.cross(sides.q_b * joint.axis_b);
    const Mat3 inverse_inertia = sides.angularMass();
    Eigen::Matrix2d k;
    for (int i = 0; i < 2; ++i) {
      for (int j = 0; j < 2; ++j) k(i, j) = p[i].dot(inverse_inertia * p[j]);
    }
    const RowScale angular = rowScale(row.softness, pass.use_bias);
    const Vec3 w = sides.relativeAngularVelocity();
    const Eigen::Vector2d rhs(p[0].dot(w) + angular.bias_rate * p[0].dot(error),
                              p[1].dot(w) + angular.bias_rate * p[1].dot(error));
    const Eigen::Vector2d total(p[0].dot(joint.angular_impulse), p[1].dot(joint.angular_impulse));
    const Eigen::Vector2d lambda =
        -angular.mass_scale * k.completeOrthogonalDecomposition().solve(rhs) -
        angular.impulse_scale * total;
    const Vec3 impulse = lambda[0] * p[0] + lambda[1] * p[1];
    joint.angular_impulse = (total[0] + lambda[0]) * p[0] + (total[1] + lambda[1]) * p[1];
    sides.applyAngular(impulse);
  }
  const RowScale scale = rowScale(row.softness, pass.use_bias);
  const Vec3 bias = scale.bias_rate * sides.pointError();
  const Vec3 impulse =
      -scale.mass_scale * solveMass(sides.pointMass(), sides.pointVelocity() + bias) -
      scale.impulse_scale * joint.linear_impulse;
  joint.linear_impulse += impulse;
  sides.applyLinear(impulse);
}

JointReaction JointKind<HingeJoint>::reaction(const HingeJoint& joint, const Real h) {
  const Vec3 axial =
      (joint.motor_impulse + joint.lower_impulse - joint.upper_impulse) * joint.world_axis;
  return JointReaction{joint.id, joint.linear_impulse / h, (joint.angular_impulse + axial) / h};
}

void JointKind<HingeJoint>::addToHash(const HingeJoint& joint, StateHasher& hasher) {
  hasher.add(static_cast<std::uint64_t>(joint.id));
  hasher.add(joint.linear_impulse);
  hasher.add(joint.angular_impulse);
  hasher.add(joint.lower_impulse);
  hasher.add(joint.upper_impulse);
  hasher.add(joint.motor_impulse);
}

}  // namespace engine
}  // namespace mass_aggregate_sim
