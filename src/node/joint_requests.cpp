#include "mass_aggregate_sim/node/joint_requests.h"

#include <cmath>
#include <sstream>

#include "mass_aggregate_sim/node/body_requests.h"
#include "mass_aggregate_sim/node/input_limits.h"
#include "mass_aggregate_sim/node/links.h"

namespace mass_aggregate_sim {
namespace node {

using engine::JointId;
using engine::Real;
using engine::Result;
using engine::Status;
using engine::Vec3;

namespace {

std::string number(const Real value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

// Lists a kind's fields (JointKind<K>::fields) with their meaning.
class FieldList {
 public:
  std::vector<JointField> fields;
  void direction(const char* name, const Vec3&) { add(name, JointFieldMeaning::kDirection); }
  void flag(const char* name, const bool&) { add(name, JointFieldMeaning::kFlag); }
  void angle(const char* name, const Real&) { add(name, JointFieldMeaning::kAngle); }
  void rate(const char* name, const Real&) { add(name, JointFieldMeaning::kRate); }
  void magnitude(const char* name, const Real&) { add(name, JointFieldMeaning::kMagnitude); }
  void length(const char* name, const Real&) { add(name, JointFieldMeaning::kLength); }

 private:
  void add(const char* name, const JointFieldMeaning meaning) {
    fields.push_back(JointField{name, meaning});
  }
};

// Sets a kind's fields from the values a request gave, each within the node's bounds.
class FieldSetter {
 public:
  FieldSetter(const JointValues& values, const bool every_field)
      : values_(values), every_field_(every_field) {}
  Status status = Status::ok();

  void direction(const char* name, Vec3& value) {
    if (take(values_.directions, name, value)) {
      keep(checkVector(value, kMaxLength, name, ""));
    }
  }
  void flag(const char* name, bool& value) { take(values_.flags, name, value); }
  void angle(const char* name, Real& value) {
    if (take(values_.numbers, name, value)) keep(bounded(name, value, -M_PI, M_PI, "rad"));
  }
  void rate(const char* name, Real& value) {
    if (take(values_.numbers, name, value)) {
      keep(bounded(name, value, -kMaxAngularSpeed, kMaxAngularSpeed, "rad/s"));
    }
  }
  void magnitude(const char* name, Real& value) {
    if (take(values_.numbers, name, value)) keep(bounded(name, value, 0.0, kMaxTorque, ""));
  }
  void length(const char* name, Real& value) {
    if (!take(values_.numbers, name, value)) return;
    if (!std::isfinite(value)) {
      keep(Status::error(std::string(name) + ": must be finite"));
    } else if (value > kMaxLength) {
      keep(Status::error(std::string(name) + ": must be at most " + number(kMaxLength) +
                         " m (negative: the distance now)"));
    }
  }

 private:
  template <typename Map, typename T>
  bool take(const Map& map, const char* name, T& value) {
    const auto it = map.find(name);
    if (it == map.end()) {
      if (every_field_) keep(Status::error(std::string(name) + ": not given"));
      return false;
    }
    value = it->second;
    return true;
  }
  static Status bounded(const char* name, const Real value, const Real low, const Real high,
                        const char* unit) {
    if (!std::isfinite(value)) return Status::error(std::string(name) + ": must be finite");
    if (value < low || value > high) {
      return Status::error(std::string(name) + ": must be in [" + number(low) + ", " +
                           number(high) + "] " + unit + ", got " + number(value));
    }
    return Status::ok();
  }
  void keep(const Status& s) {
    if (status && !s) status = s;
  }
  const JointValues& values_;
  bool every_field_;
};

template <typename Kind>
bool containsJoint(const std::vector<Kind>& joints, const JointId id) {
  for (const Kind& joint : joints) {
    if (joint.id == id) return true;
  }
  return false;
}

}  // namespace

Result<engine::JointEnd> resolveJointEnd(const engine::World& world, const JointEndRef& ref,
                                         const Vec3& anchor, const char* field) {
  const std::string where = std::string(field) + ": ";
  switch (ref.kind) {
    case JointEndRef::Kind::kWorld: {
      const Status valid = checkPosition(anchor, std::string(field) + " anchor");
      if (!valid) return valid;
      return engine::JointEnd::inWorld(anchor);
    }
    case JointEndRef::Kind::kBody: {
      const Status valid = checkPosition(anchor, std::string(field) + " anchor");
      if (!valid) return valid;
      const auto body = resolveBody(world, BodyRef{ref.id, ref.name});
      if (!body) return Status::error(where + body.message());
      const std::size_t dense = *world.bodies().find(*body);
      return engine::JointEnd::onBody(*body, world.bodies().pose(dense).applyInverse(anchor));
    }
    case JointEndRef::Kind::kParticle: {
      const auto particle = resolveParticle(world, ParticleRef{ref.id, ref.name});
      if (!particle) return Status::error(where + particle.message());
      return engine::JointEnd::atParticle(*particle);
    }
  }
  return Status::error(where + "unknown kind of end");
}

std::optional<std::vector<JointField>> jointFields(const std::string& type) {
  std::optional<std::vector<JointField>> out;
  engine::forEachKind(engine::JointKinds{}, [&](const auto tag) {
    using Kind = typename decltype(tag)::type;
    if (out || type != engine::JointKind<Kind>::kName) return;
    Kind joint;
    FieldList list;
    engine::JointKind<Kind>::fields(joint, list);
    out = list.fields;
  });
  return out;
}

std::string jointTypeNames() {
  std::string names;
  engine::forEachKind(engine::JointKinds{}, [&](const auto tag) {
    using Kind = typename decltype(tag)::type;
    names += (names.empty() ? "" : ", ") + std::string(engine::JointKind<Kind>::kName);
  });
  return names;
}

Result<JointId> addJoint(engine::World& world, const JointRequest& request) {
  bool known = false;
  Result<JointId> added = Status::error("");
  engine::forEachKind(engine::JointKinds{}, [&](const auto tag) {
    using Kind = typename decltype(tag)::type;
    if (known || request.type != engine::JointKind<Kind>::kName) return;
    known = true;
    Kind joint;
    FieldSetter setter(request.values, request.every_field);
    engine::JointKind<Kind>::fields(joint, setter);
    if (!setter.status) {
      added = setter.status;
      return;
    }
    const auto a = resolveJointEnd(world, request.a, request.anchor_a, "a");
    if (!a) {
      added = a.status();
      return;
    }
    const auto b = resolveJointEnd(world, request.b, request.anchor_b, "b");
    if (!b) {
      added = b.status();
      return;
    }
    joint.a = *a;
    joint.b = *b;
    joint.collide_connected = request.collide_connected;
    added = world.addJoint(joint);
  });
  if (!known) {
    return Status::error("type: unknown joint type " + quoteInput(request.type) +
                         " (known: " + jointTypeNames() + ")");
  }
  return added;
}

Status checkJointName(const std::string& name, const JointNames& taken) {
  if (name.size() > kMaxNameLength) {
    return Status::error("name: at most " + std::to_string(kMaxNameLength) + " characters, got " +
                         std::to_string(name.size()));
  }
  for (const char c : name) {
    if (c <= ' ' || c > '~') {
      return Status::error("name: only printable ASCII characters without spaces");
    }
  }
  const std::string prefix = "joint_";
  if (name.rfind(prefix, 0) == 0 && name.size() > prefix.size() &&
      name.find_first_not_of("0123456789", prefix.size()) == std::string::npos) {
    return Status::error("name: " + quoteInput(name) +
                         " is kept for a joint without a name (joint_<id>)");
  }
  for (const auto& [id, other] : taken) {
    if (other == name) return Status::error("name: " + quoteInput(name) + " is already taken");
  }
  return Status::ok();
}

std::string jointName(const JointNames& names, const JointId id) {
  const auto it = names.find(id);
  return it != names.end() ? it->second : "joint_" + std::to_string(id);
}

bool hasJoint(const engine::World& world, const JointId id) {
  bool found = false;
  world.joints().forEach([&](const auto& kind) { found = found || containsJoint(kind, id); });
  return found;
}

std::optional<JointId> findJoint(const engine::World& world, const JointNames& names,
                                 const std::string& name) {
  for (const auto& [id, given] : names) {
    if (given == name) return hasJoint(world, id) ? std::optional<JointId>(id) : std::nullopt;
  }
  const std::string prefix = "joint_";
  if (name.rfind(prefix, 0) != 0 || name.size() == prefix.size() || name.size() > 16 ||
      name.find_first_not_of("0123456789", prefix.size()) != std::string::npos) {
    return std::nullopt;
  }
  const unsigned long long id = std::stoull(name.substr(prefix.size()));
  if (id > 0xFFFFFFFFull || names.count(static_cast<JointId>(id))) return std::nullopt;
  if (!hasJoint(world, static_cast<JointId>(id))) return std::nullopt;
  return static_cast<JointId>(id);
}

void pruneJointNames(const engine::World& world, JointNames& names) {
  for (auto it = names.begin(); it != names.end();) {
    it = hasJoint(world, it->first) ? std::next(it) : names.erase(it);
  }
}

}  // namespace node
}  // namespace mass_aggregate_sim
