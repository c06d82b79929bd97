#pragma once

#include "mass_aggregate_sim/engine/joints/joint_kind.h"

namespace mass_aggregate_sim {
namespace engine {

// Holds anchor a and anchor b together and lets b turn relative to a about one axis only (a
// revolute joint), optionally within limits and driven by a motor. The angle is b's turn about
// the axis since the joint was added (right-handed about `axis`).
struct HingeJoint {
  JointEnd a;
  JointEnd b;
  Vec3 axis = Vec3::UnitZ();  // in the world, when added (normalised)
  bool limit = false;
  Real lower = 0.0;  // rad, in [-pi, pi]
  Real upper = 0.0;  // rad, lower <= upper <= pi
  bool motor = false;
  Real motor_speed = 0.0;       // rad/s, the speed the motor drives b at relative to a
  Real max_motor_torque = 0.0;  // N m
  bool collide_connected = false;
  JointId id = 0;
  // Measured when added: the axis in each side's mass frame and b's orientation relative to a.
  Vec3 axis_a = Vec3::UnitZ();
  Vec3 axis_b = Vec3::UnitZ();
  Quat reference = Quat::Identity();
  // State: the last substep's impulses.
  Vec3 linear_impulse = Vec3::Zero();
  Vec3 angular_impulse = Vec3::Zero();  // about the two axes perpendicular to the hinge's
  Real lower_impulse = 0.0;
  Real upper_impulse = 0.0;
  Real motor_impulse = 0.0;
  Vec3 world_axis = Vec3::UnitZ();  // a's axis in the world at the last pass (for reactions)
};

class StateHasher;

template <>
struct JointKind<HingeJoint> {
  static constexpr const char* kName = "hinge";
  static constexpr bool kTurns = true;
  template <typename Visitor>
  static void fields(HingeJoint& joint, Visitor& visit) {
    visit.direction("axis", joint.axis);
    visit.flag("limit", joint.limit);
    visit.angle("lower", joint.lower);
    visit.angle("upper", joint.upper);
    visit.flag("motor", joint.motor);
    visit.rate("motor_speed", joint.motor_speed);
    visit.magnitude("max_motor_torque", joint.max_motor_torque);
  }
  static Status validate(HingeJoint& joint, const JointScene& scene);
  static void warmStart(const HingeJoint& joint, const JointRow& row,
                        std::vector<SolverBody>& bodies);
  static void solve(HingeJoint& joint, const JointRow& row, const JointPass& pass);
  static JointReaction reaction(const HingeJoint& joint, Real h);
  static void addToHash(const HingeJoint& joint, StateHasher& hasher);
  // The hinge's angle now (rad, in (-pi, pi]) from the two sides' mass frame orientations.
  static Real angle(const HingeJoint& joint, const Quat& q_a, const Quat& q_b);
};

}  // namespace engine
}  // namespace mass_aggregate_sim
