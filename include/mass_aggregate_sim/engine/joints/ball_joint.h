#pragma once

#include "mass_aggregate_sim/engine/joints/joint_kind.h"

namespace mass_aggregate_sim {
namespace engine {

// Holds anchor a and anchor b together; rotation is free (a ball-and-socket). Between two bodies,
// a body and a particle, or a body and the world.
struct BallJoint {
  JointEnd a;
  JointEnd b;
  bool collide_connected = false;
  JointId id = 0;
  Vec3 linear_impulse = Vec3::Zero();  // state: the last substep's, for warm starting
};

class StateHasher;

template <>
struct JointKind<BallJoint> {
  static constexpr const char* kName = "ball";
  static constexpr bool kTurns = false;
  template <typename Visitor>
  static void fields(BallJoint&, Visitor&) {}
  static Status validate(BallJoint& joint, const JointScene& scene);
  static void warmStart(const BallJoint& joint, const JointRow& row,
                        std::vector<SolverBody>& bodies);
  static void solve(BallJoint& joint, const JointRow& row, const JointPass& pass);
  static JointReaction reaction(const BallJoint& joint, Real h);
  static void addToHash(const BallJoint& joint, StateHasher& hasher);
};

}  // namespace engine
}  // namespace mass_aggregate_sim
