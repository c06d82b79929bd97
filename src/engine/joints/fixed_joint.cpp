// The fixed joint kind (fixed_joint.h).
#include "mass_aggregate_sim/engine/joints/fixed_joint.h"

#include "engine/core/state_hash.h"
#include "engine/joints/end_frames.h"
#include "engine/joints/joint_math.h"

namespace mass_aggregate_sim {
namespace engine {

Status JointKind<FixedJoint>::validate(FixedJoint& joint, const JointScene& scene) {
  joint.reference =
      endOrientation(joint.a, scene.bodies).conjugate() * endOrientation(joint.b, scene.bodies);
  joint.linear_impulse.setZero();
  joint.angular_impulse.setZero();
  return Status::ok();
}

void JointKind<FixedJoint>::warmStart(const FixedJoint& joint, const JointRow& row,
                                      std::vector<SolverBody>& bodies) {
  JointSides sides(row, bodies);
  sides.applyLinear(joint.linear_impulse);
  sides.applyAngular(joint.angular_impulse);
}

void JointKind<FixedJoint>::solve(FixedJoint& joint, const JointRow& row, const JointPass& pass) {
  JointSides sides(row, pass.bodies);
  const RowScale scale = rowScale(row.softness, pass.use_bias);
  {
    // The turn b is off its place by, in the world: q_b (q_a reference)^-1 = (cos, sin n) gives
    // C = 2 sin(angle / 2) n, the small-angle rotation vector (the shorter way round).
    Quat error = sides.q_b * (sides.q_a * joint.reference).conjugate();
    if (error.w() < 0.0) error.coeffs() = -error.coeffs();
    const Vec3 c = 2.0 * error.vec();
    const Vec3 impulse =
        -scale.mass_scale *
            solveMass(sides.angularMass(), sides.relativeAngularVelocity() + scale.bias_rate * c) -
        scale.impulse_scale * joint.angular_impulse;
    joint.angular_impulse += impulse;
    sides.applyAngular(impulse);
  }
  const Vec3 impulse =
      -scale.mass_scale * solveMass(sides.pointMass(),
                                    sides.pointVelocity() + scale.bias_rate * sides.pointError()) -
      scale.impulse_scale * joint.linear_impulse;
  joint.linear_impulse += impulse;
  sides.applyLinear(impulse);
}

JointReaction JointKind<FixedJoint>::reaction(const FixedJoint& joint, const Real h) {
  return JointReaction{joint.id, joint.linear_impulse / h, joint.angular_impulse / h};
}

void JointKind<FixedJoint>::addToHash(const FixedJoint& joint, StateHasher& hasher) {
  hasher.add(static_cast<std::uint64_t>(joint.id));
  hasher.add(joint.linear_impulse);
  hasher.add(joint.angular_impulse);
}

}  // namespace engine
}  // namespace mass_aggregate_sim
