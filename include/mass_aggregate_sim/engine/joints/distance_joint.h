#pragma once

#include "mass_aggregate_sim/engine/joints/joint_kind.h"

namespace mass_aggregate_sim {
namespace engine {

// Keeps the distance between anchor a and anchor b within [min_length, max_length]: a rod when
// they are equal, a cable (pulls only) with min_length 0. The particles' cable and rod, with ends
// on bodies. A negative length is the distance when added.
struct DistanceJoint {
  JointEnd a;
  JointEnd b;
  Real min_length = -1.0;  // m
  Real max_length = -1.0;  // m
  bool collide_connected = false;
  JointId id = 0;
  Real lower_impulse = 0.0;              // pushing apart (at min_length)
  Real upper_impulse = 0.0;              // pulling together (at max_length)
  Vec3 world_direction = Vec3::UnitZ();  // from a to b at the last pass (for reactions)

  static DistanceJoint rod(const JointEnd& a, const JointEnd& b, const Real length = -1.0) {
    DistanceJoint j;
    j.a = a;
    j.b = b;
    j.min_length = length;
    j.max_length = length;
    return j;
  }
  static DistanceJoint cable(const JointEnd& a, const JointEnd& b, const Real length = -1.0) {
    DistanceJoint j;
    j.a = a;
    j.b = b;
    j.min_length = 0.0;
    j.max_length = length;
    return j;
  }
};

class StateHasher;

template <>
struct JointKind<DistanceJoint> {
  static constexpr const char* kName = "distance";
  static constexpr bool kTurns = false;
  template <typename Visitor>
  static void fields(DistanceJoint& joint, Visitor& visit) {
    visit.length("min_length", joint.min_length);
    visit.length("max_length", joint.max_length);
  }
  static Status validate(DistanceJoint& joint, const JointScene& scene);
  static void warmStart(const DistanceJoint& joint, const JointRow& row,
                        std::vector<SolverBody>& bodies);
  static void solve(DistanceJoint& joint, const JointRow& row, const JointPass& pass);
  static JointReaction reaction(const DistanceJoint& joint, Real h);
  static void addToHash(const DistanceJoint& joint, StateHasher& hasher);
};

}  // namespace engine
}  // namespace mass_aggregate_sim
