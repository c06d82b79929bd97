#pragma once
// Joints as the node's requests and scenes give them, without ROS. A joint kind's own fields
// (JointKind<K>::fields: a hinge's axis, limits and motor, a distance joint's lengths) are read
// by name and meaning, so a kind added to JointKinds needs no change here.

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "mass_aggregate_sim/engine/world/world.h"

namespace mass_aggregate_sim {
namespace node {

// One end of a joint in a request: the world, a body or a particle, by name when the name is
// non-empty, else by packed id.
struct JointEndRef {
  enum class Kind { kWorld, kBody, kParticle };
  Kind kind = Kind::kWorld;
  std::uint64_t id = 0;
  std::string name;
};

// What a kind's field means, as JointKind<K>::fields names it: a direction (Vec3), a flag (bool),
// or a number (an angle in rad, a rate in rad/s, a magnitude in N m, a length in m).
enum class JointFieldMeaning { kDirection, kFlag, kAngle, kRate, kMagnitude, kLength };
struct JointField {
  std::string name;
  JointFieldMeaning meaning;
};
// The fields of the kind named `type`, in the order it declares them; nothing for an unknown type.
std::optional<std::vector<JointField>> jointFields(const std::string& type);
// Every kind's name, comma separated.
std::string jointTypeNames();

// The values a request or a scene gives a kind's fields, by name, in the world frame.
struct JointValues {
  std::map<std::string, engine::Vec3> directions;
  std::map<std::string, bool> flags;
  std::map<std::string, engine::Real> numbers;
};

// The engine's end for `ref` holding the world point `anchor` (a body keeps it in its own frame,
// a particle is itself, the world is the point); `field` names the end in refusals.
engine::Result<engine::JointEnd> resolveJointEnd(const engine::World& world, const JointEndRef& ref,
                                                 const engine::Vec3& anchor, const char* field);

struct JointRequest {
  std::string type;
  std::string name;  // empty: the joint is shown as joint_<id>
  JointEndRef a;
  JointEndRef b;
  // World points where the joint holds end a and end b (a body end keeps the point in its own
  // frame; a particle end is the particle; a world end is the point itself).
  engine::Vec3 anchor_a = engine::Vec3::Zero();
  engine::Vec3 anchor_b = engine::Vec3::Zero();
  JointValues values;
  // A field the kind declares but `values` lacks: refused when true (a request must carry every
  // field), else the kind's default (a scene names only what it needs).
  bool every_field = false;
  bool collide_connected = false;
};

// The node's bounds on every field by meaning (finite; angles within +-pi, rates within
// kMaxAngularSpeed, magnitudes in [0, kMaxTorque], lengths at most kMaxLength, negative meaning
// the distance now, direction components within +-kMaxLength), the ends resolved and checked, then
// the engine's own checks; adds the joint or changes nothing.
engine::Result<engine::JointId> addJoint(engine::World& world, const JointRequest& request);

// Joint names: unique among joints, at most kMaxNameLength printable characters; joint_<digits>
// is kept for the joints without a name.
using JointNames = std::map<engine::JointId, std::string>;
engine::Status checkJointName(const std::string& name, const JointNames& taken);
// Its name, or joint_<id>.
std::string jointName(const JointNames& names, engine::JointId id);
// The id of the joint named so (explicitly or as joint_<id>), if the world has it.
std::optional<engine::JointId> findJoint(const engine::World& world, const JointNames& names,
                                         const std::string& name);
bool hasJoint(const engine::World& world, engine::JointId id);
// Drops the names of joints the world no longer has (removed with a body or a particle).
void pruneJointNames(const engine::World& world, JointNames& names);

}  // namespace node
}  // namespace mass_aggregate_sim
