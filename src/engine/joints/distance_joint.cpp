// The distance joint kind (distance_joint.h).
#include "mass_aggregate_sim/engine/joints/distance_joint.h"

#include <algorithm>
#include <cmath>

#include "engine/core/state_hash.h"
#include "engine/joints/end_frames.h"
#include "engine/joints/joint_math.h"

namespace mass_aggregate_sim {
namespace engine {

Status JointKind<DistanceJoint>::validate(DistanceJoint& joint, const JointScene& scene) {
  const Real now = (endPosition(joint.b, scene) - endPosition(joint.a, scene)).norm();
  Real& low = joint.min_length;
  Real& high = joint.max_length;
  if (!std::isfinite(low) || !std::isfinite(high)) {
    return Status::error("distance min_length and max_length must be finite");
  }
  // A negative length is the distance now (both, when a rod's length is left to measure).
  if (high < 0.0) high = now;
  if (low < 0.0) low = now;
  if (low > high) return Status::error("distance min_length must be <= max_length");
  joint.lower_impulse = joint.upper_impulse = 0.0;
  return Status::ok();
}

void JointKind<DistanceJoint>::warmStart(const DistanceJoint& joint, const JointRow& row,
                                         std::vector<SolverBody>& bodies) {
  JointSides sides(row, bodies);
  const Vec3 d = sides.pointError();
  const Real length = d.norm();
  const Vec3 n = length > 1e-12 ? Vec3(d / length) : joint.world_direction;
  sides.applyLinear((joint.lower_impulse - joint.upper_impulse) * n);
}

void JointKind<DistanceJoint>::solve(DistanceJoint& joint, const JointRow& row,
                                     const JointPass& pass) {
  JointSides sides(row, pass.bodies);
  const Vec3 d = sides.pointError();
  const Real length = d.norm();
  const Vec3 n = length > 1e-12 ? Vec3(d / length) : joint.world_direction;
  joint.world_direction = n;
  const Real k = n.dot(sides.pointMass() * n);
  const Real mass = k > 0.0 ? 1.0 / k : 0.0;
  // Each bound holds C >= 0 with an impulse >= 0: the lower one pushes b away from a along n
  // (C = l - min), the upper one pulls (C = max - l). A bound not reached is speculative.
  const auto bound = [&](const Real c, const Real sign, Real& total) {
    Real bias = 0.0;
    Real mass_scale = 1.0;
    Real impulse_scale = 0.0;
    if (c > 0.0) {
      bias = c / pass.h;
    } else if (pass.use_bias) {
      bias = row.softness.bias_rate * c;
      mass_scale = row.softness.mass_scale;
      impulse_scale = row.softness.impulse_scale;
    }
    const Real c_dot = sign * n.dot(sides.pointVelocity());
    const Real impulse = -mass * mass_scale * (c_dot + bias) - impulse_scale * total;
    const Real updated = std::max(total + impulse, 0.0);
    sides.applyLinear(sign * (updated - total) * n);
    total = updated;
  };
  if (joint.min_length > 0.0) bound(length - joint.min_length, 1.0, joint.lower_impulse);
  bound(joint.max_length - length, -1.0, joint.upper_impulse);
}

JointReaction JointKind<DistanceJoint>::reaction(const DistanceJoint& joint, const Real h) {
  return JointReaction{joint.id,
                       (joint.lower_impulse - joint.upper_impulse) / h * joint.world_direction,
                       Vec3::Zero()};
}

void JointKind<DistanceJoint>::addToHash(const DistanceJoint& joint, StateHasher& hasher) {
  hasher.add(static_cast<std::uint64_t>(joint.id));
  hasher.add(joint.lower_impulse);
  hasher.add(joint.upper_impulse);
}

}  // namespace engine
}  // namespace mass_aggregate_sim
