#pragma once

#include "mass_aggregate_sim/engine/core/kind_list.h"
#include "mass_aggregate_sim/engine/joints/ball_joint.h"
#include "mass_aggregate_sim/engine/joints/distance_joint.h"
#include "mass_aggregate_sim/engine/joints/fixed_joint.h"
#include "mass_aggregate_sim/engine/joints/hinge_joint.h"

namespace mass_aggregate_sim {
namespace engine {

// Every joint kind, in the order the solver passes over them (before the contacts).
using JointKinds = KindList<BallJoint, HingeJoint, FixedJoint, DistanceJoint>;

// A world's joints: one array per kind.
using Joints = KindArrays<JointKinds>;

}  // namespace engine
}  // namespace mass_aggregate_sim
