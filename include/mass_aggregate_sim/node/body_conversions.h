#pragma once
// Bodies and joints between ROS messages and the node's requests.

#include <geometry_msgs/Pose.h>
#include <geometry_msgs/Twist.h>
#include <sensor_msgs/JointState.h>

#include "mass_aggregate_sim/AddBodySpring.h"
#include "mass_aggregate_sim/AddJoint.h"
#include "mass_aggregate_sim/BodyArray.h"
#include "mass_aggregate_sim/BodyContactArray.h"
#include "mass_aggregate_sim/BodySpec.h"
#include "mass_aggregate_sim/JointEndSpec.h"
#include "mass_aggregate_sim/engine/world/world.h"
#include "mass_aggregate_sim/node/body_requests.h"
#include "mass_aggregate_sim/node/body_snapshot.h"
#include "mass_aggregate_sim/node/body_springs.h"
#include "mass_aggregate_sim/node/joint_requests.h"

namespace mass_aggregate_sim {
namespace node {

// The quaternion as given (not normalised: requests check it).
engine::Transform fromMsg(const geometry_msgs::Pose& pose);
geometry_msgs::Pose toPoseMsg(const engine::Transform& pose);
Twist fromMsg(const geometry_msgs::Twist& twist);
geometry_msgs::Twist toTwistMsg(const Twist& twist);

// A spawn request's body as an engine spec in its own frame_id, with its twist (of the frame's
// origin) left for the caller to place: refuses an unknown type or shape type, reads each shape
// kind's fields (BodyShapeKind<K>::fields) from the message fields of the same name; density 0
// means 1000 kg/m^3. Bounds are checkBodySpec's.
engine::Result<engine::BodySpec> toBodySpec(const BodySpec& msg);

engine::Result<JointEndRef> toJointEnd(const JointEndSpec& msg, const char* field);
// An AddJoint request as the node takes it, with anchors and directions as given (in frame_id):
// every field a kind may declare is filled from the message field of the same name
// (every_field: a kind declaring a field the message lacks is refused).
engine::Result<JointRequest> toJointRequest(const AddJoint::Request& msg);
// The request's anchors and directions moved from `frame` into the world; the message updated to
// match (frame_id cleared), as it is recorded.
void placeJointRequest(const ReferenceFrame& frame, JointRequest& request, AddJoint::Request& msg);

// An ~add_body_spring request with its anchors in its own frame_id: the type and the ends' kinds
// checked (the numbers and the ends themselves are addBodySpring's).
engine::Result<BodySpringRequest> toBodySpringRequest(const AddBodySpring::Request& msg);
// The anchors moved from `frame` into the world; the message updated to match (frame_id
// cleared), as it is recorded.
void placeBodySpringRequest(const ReferenceFrame& frame, BodySpringRequest& request,
                            AddBodySpring::Request& msg);

// Every body; the header's stamp and frame are left for the caller.
void fillBodyArray(const BodySnapshot& bodies, std::uint64_t step, double time, BodyArray& msg);
// Every body contact; names of bodies from the snapshot, of particles from `particle_names`
// (indexed like `particle_ids`).
void fillContacts(const BodySnapshot& bodies, const std::vector<std::uint64_t>& particle_ids,
                  const std::vector<std::string>& particle_names, std::uint64_t step, double time,
                  BodyContactArray& msg);
// Every hinge: name, angle, velocity, effort.
void fillJointStates(const BodySnapshot& bodies, sensor_msgs::JointState& msg);

}  // namespace node
}  // namespace mass_aggregate_sim
