// The ball joint kind (ball_joint.h).
#include "mass_aggregate_sim/engine/joints/ball_joint.h"

#include "engine/core/state_hash.h"
#include "engine/joints/joint_math.h"

namespace mass_aggregate_sim {
namespace engine {

Status JointKind<BallJoint>::validate(BallJoint& joint, const JointScene&) {
  joint.linear_impulse.setZero();
  return Status::ok();
}

void JointKind<BallJoint>::warmStart(const BallJoint& joint, const JointRow& row,
                                     std::vector<SolverBody>& bodies) {
  JointSides sides(row, bodies);
  sides.applyLinear(joint.linear_impulse);
}

void JointKind<BallJoint>::solve(BallJoint& joint, const JointRow& row, const JointPass& pass) {
  JointSides sides(row, pass.bodies);
  const RowScale scale = rowScale(row.softness, pass.use_bias);
  // lambda = -s_m K^-1 (dC/dt + bias_rate C) - s_i lambda_total
  const Vec3 bias = scale.bias_rate * sides.pointError();
  const Vec3 impulse =
      -scale.mass_scale * solveMass(sides.pointMass(), sides.pointVelocity() + bias) -
      scale.impulse_scale * joint.linear_impulse;
  joint.linear_impulse += impulse;
  sides.applyLinear(impulse);
}

JointReaction JointKind<BallJoint>::reaction(const BallJoint& joint, const Real h) {
  return JointReaction{joint.id, joint.linear_impulse / h, Vec3::Zero()};
}

void JointKind<BallJoint>::addToHash(const BallJoint& joint, StateHasher& hasher) {
  hasher.add(static_cast<std::uint64_t>(joint.id));
  hasher.add(joint.linear_impulse);
}

}  // namespace engine
}  // namespace mass_aggregate_sim
