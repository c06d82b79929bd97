#pragma once

#include "mass_aggregate_sim/engine/joints/joint_kind.h"

namespace mass_aggregate_sim {
namespace engine {

// Holds b where it was relative to a when added: anchors together and orientations kept (a weld).
struct FixedJoint {
  JointEnd a;
  JointEnd b;
  bool collide_connected = false;
  JointId id = 0;
  Quat reference = Quat::Identity();  // measured when added: b's orientation relative to a
  Vec3 linear_impulse = Vec3::Zero();
  Vec3 angular_impulse = Vec3::Zero();
};

class StateHasher;

template <>
struct JointKind<FixedJoint> {
  static constexpr const char* kName = "fixed";
  static constexpr bool kTurns = true;
  template <typename Visitor>
  static void fields(FixedJoint&, Visitor&) {}
  static Status validate(FixedJoint& joint, const JointScene& scene);
  static void warmStart(const FixedJoint& joint, const JointRow& row,
                        std::vector<SolverBody>& bodies);
  static void solve(FixedJoint& joint, const JointRow& row, const JointPass& pass);
  static JointReaction reaction(const FixedJoint& joint, Real h);
  static void addToHash(const FixedJoint& joint, StateHasher& hasher);
};

}  // namespace engine
}  // namespace mass_aggregate_sim
