#include "mass_aggregate_sim/node/scene_bodies.h"

#include <utility>
#include <vector>

#include "mass_aggregate_sim/node/body_requests.h"
#include "mass_aggregate_sim/node/body_springs.h"
#include "mass_aggregate_sim/node/input_limits.h"
#include "mass_aggregate_sim/node/xmlrpc_reader.h"

namespace mass_aggregate_sim {
namespace node {
namespace {

using engine::Real;
using engine::Vec3;
using XmlRpc::XmlRpcValue;

std::string indexed(const std::string& key, const int i) {
  return key + "[" + std::to_string(i) + "]";
}

// [x, y, z, w], as in geometry_msgs/Quaternion.
engine::Quat quaternionOr(XmlRpcValue& s, const std::string& key, const char* member,
                          const engine::Quat& fallback) {
  if (!has(s, member)) return fallback;
  XmlRpcValue& q = s[member];
  const std::string qk = key + "." + member;
  requireArray(q, qk);
  if (q.size() != 4) throw ParamError(qk, "expected a quaternion [x, y, z, w]");
  return engine::Quat(readReal(q[3], indexed(qk, 3)), readReal(q[0], indexed(qk, 0)),
                      readReal(q[1], indexed(qk, 1)), readReal(q[2], indexed(qk, 2)));
}

// The names of a body shape kind's fields, for the key check.
class ShapeFieldNames {
 public:
  std::vector<std::string> names{"type",    "position", "orientation",
                                 "density", "friction", "restitution"};
  void length(const char* name, const Real&) { names.emplace_back(name); }
  void extents(const char* name, const Vec3&) { names.emplace_back(name); }
};

// Reads a body shape kind's fields from its scene entry by what they mean (bounds: checkBodySpec).
class ShapeFieldReader {
 public:
  ShapeFieldReader(XmlRpcValue& entry, std::string key) : entry_(entry), key_(std::move(key)) {}
  void length(const char* name, Real& value) { value = realOr(entry_, key_, name, value); }
  void extents(const char* name, Vec3& value) { value = vec3Or(entry_, key_, name, value); }

 private:
  XmlRpcValue& entry_;
  std::string key_;
};

engine::BodyShapeSpec readShape(XmlRpcValue& s, const std::string& k) {
  requireStruct(s, k);
  const std::string type = stringOr(s, k, "type", "");
  engine::BodyShapeSpec shape;
  bool known = false;
  engine::forEachKind(engine::BodyShapeKinds{}, [&](const auto tag) {
    using Shape = typename decltype(tag)::type;
    if (known || type != engine::BodyShapeKind<Shape>::kName) return;
    known = true;
    Shape probe;
    ShapeFieldNames names;
    engine::BodyShapeKind<Shape>::fields(probe, names);
    checkKeys(s, k, names.names);
  });
  if (!known) {
    throw ParamError(k + ".type",
                     "unknown shape " + quoteInput(type) + " (known: " + bodyShapeNames() + ")");
  }
  ShapeFieldReader reader(s, k);
  shape.geometry = *readBodyShape(type, reader);
  shape.local.position = vec3Or(s, k, "position", Vec3::Zero());
  shape.local.rotation = quaternionOr(s, k, "orientation", engine::Quat::Identity());
  shape.density = realOr(s, k, "density", shape.density);
  shape.material.friction = realOr(s, k, "friction", shape.material.friction);
  shape.material.restitution = realOr(s, k, "restitution", shape.material.restitution);
  return shape;
}

// The body or particle a joint's end names, or the world for an empty name.
JointEndRef endNamed(const engine::World& world, const std::string& name, const std::string& k) {
  JointEndRef end;
  if (name.empty()) return end;
  end.name = name;
  if (world.bodies().findByName(name)) {
    end.kind = JointEndRef::Kind::kBody;
  } else if (world.particles().findByName(name)) {
    end.kind = JointEndRef::Kind::kParticle;
  } else {
    throw ParamError(k, "no body or particle named " + quoteInput(name));
  }
  return end;
}

// A body spec's refusal under the scene's key names (checkBodySpec names a request's fields).
engine::Status sceneKeys(const engine::Status& status) {
  if (status) return status;
  std::string message = status.message();
  for (const auto& [field, key] : {std::pair<const char*, const char*>{"pose.position", "position"},
                                   {"pose.orientation", "orientation"},
                                   {"twist.linear", "velocity"},
                                   {"twist.angular", "angular_velocity"},
                                   {"twist", "velocity"}}) {
    const std::string prefix = std::string(field) + ": ";
    if (message.rfind(prefix, 0) == 0) {
      message = std::string(key) + ": " + message.substr(prefix.size());
      break;
    }
  }
  return engine::Status::error(message);
}

}  // namespace

void readBodySolver(XmlRpcValue& s, const std::string& k, engine::World& world) {
  checkKeys(s, k,
            {"substeps", "iterations", "relax_iterations", "contact_hertz", "contact_damping_ratio",
             "joint_hertz", "joint_damping_ratio", "max_push_speed", "speculative_distance",
             "linear_slop", "min_twist_lever", "restitution_threshold", "sleep", "sleep_speed",
             "time_to_sleep", "continuous", "gyroscopic", "runaway_speed"});
  engine::BodySettings b = world.bodySettings();
  b.substeps = intOr(s, k, "substeps", b.substeps);
  b.iterations = intOr(s, k, "iterations", b.iterations);
  b.relax_iterations = intOr(s, k, "relax_iterations", b.relax_iterations);
  b.contact_hertz = realOr(s, k, "contact_hertz", b.contact_hertz);
  b.contact_damping_ratio = realOr(s, k, "contact_damping_ratio", b.contact_damping_ratio);
  b.joint_hertz = realOr(s, k, "joint_hertz", b.joint_hertz);
  b.joint_damping_ratio = realOr(s, k, "joint_damping_ratio", b.joint_damping_ratio);
  b.max_push_speed = realOr(s, k, "max_push_speed", b.max_push_speed);
  b.speculative_distance = realOr(s, k, "speculative_distance", b.speculative_distance);
  b.linear_slop = realOr(s, k, "linear_slop", b.linear_slop);
  b.min_twist_lever = realOr(s, k, "min_twist_lever", b.min_twist_lever);
  b.restitution_threshold = realOr(s, k, "restitution_threshold", b.restitution_threshold);
  b.sleep = boolOr(s, k, "sleep", b.sleep);
  b.sleep_speed = realOr(s, k, "sleep_speed", b.sleep_speed);
  b.time_to_sleep = realOr(s, k, "time_to_sleep", b.time_to_sleep);
  b.continuous = boolOr(s, k, "continuous", b.continuous);
  b.gyroscopic = boolOr(s, k, "gyroscopic", b.gyroscopic);
  b.runaway_speed = realOr(s, k, "runaway_speed", b.runaway_speed);
  const engine::Status valid = world.setBodySettings(b);
  if (!valid) throw ParamError(k, valid.message());
}

void readBodies(XmlRpcValue& list, const std::string& key, engine::World& world,
                const BodyLimits& limits) {
  requireArray(list, key);
  for (int i = 0; i < list.size(); ++i) {
    const std::string k = indexed(key, i);
    XmlRpcValue& b = list[i];
    checkKeys(b, k,
              {"name", "type", "position", "orientation", "velocity", "angular_velocity", "mass",
               "linear_damping", "angular_damping", "can_sleep", "shapes", "count", "offset"});
    engine::BodySpec spec;
    const std::string name = stringOr(b, k, "name", "");
    const std::string type = stringOr(b, k, "type", "dynamic");
    const auto parsed = parseBodyType(type);
    if (!parsed) {
      throw ParamError(k + ".type", "unknown body type " + quoteInput(type) +
                                        " (known: dynamic, kinematic, fixed)");
    }
    spec.type = *parsed;
    if (!has(b, "position")) throw ParamError(k + ".position", "is required");
    spec.pose.position = readVec3(b["position"], k + ".position");
    spec.pose.rotation = quaternionOr(b, k, "orientation", engine::Quat::Identity());
    const Twist twist{vec3Or(b, k, "velocity", Vec3::Zero()),
                      vec3Or(b, k, "angular_velocity", Vec3::Zero())};
    spec.mass = realOr(b, k, "mass", 0.0);
    spec.linear_damping = realOr(b, k, "linear_damping", 0.0);
    spec.angular_damping = realOr(b, k, "angular_damping", 0.0);
    spec.can_sleep = boolOr(b, k, "can_sleep", true);
    if (!has(b, "shapes")) throw ParamError(k + ".shapes", "is required (a list of shapes)");
    XmlRpcValue& shapes = b["shapes"];
    requireArray(shapes, k + ".shapes");
    if (static_cast<std::size_t>(shapes.size()) > kMaxShapesPerBody) {
      throw ParamError(k + ".shapes", "at most " + std::to_string(kMaxShapesPerBody) +
                                          " shapes per body, got " + std::to_string(shapes.size()));
    }
    for (int s = 0; s < shapes.size(); ++s) {
      spec.shapes.push_back(readShape(shapes[s], indexed(k + ".shapes", s)));
    }
    const bool repeated = has(b, "count");
    const int count = intOr(b, k, "count", 1);
    if (count < 1) throw ParamError(k + ".count", "must be at least 1");
    if (repeated && name.empty()) {
      throw ParamError(k + ".name", "is required with count (bodies are <name>_<i>)");
    }
    if (static_cast<std::size_t>(count) > limits.max_bodies) {
      throw ParamError(k + ".count",
                       "more than ~max_bodies (" + std::to_string(limits.max_bodies) + ")");
    }
    const Vec3 offset = vec3Or(b, k, "offset", Vec3::Zero());
    const Vec3 start = spec.pose.position;
    for (int j = 0; j < count; ++j) {
      if (world.bodies().size() >= limits.max_bodies) {
        throw ParamError(k, "the scene has more than ~max_bodies (" +
                                std::to_string(limits.max_bodies) + ") bodies");
      }
      spec.name = repeated ? name + "_" + std::to_string(j) : name;
      spec.pose.position = start + static_cast<Real>(j) * offset;
      setSpecTwist(spec, twist);
      throwIfBad(sceneKeys(checkBodySpec(spec, limits.world_frame)), k);
      if (!spec.name.empty() &&
          (world.bodies().findByName(spec.name) || world.particles().findByName(spec.name))) {
        throw ParamError(k + ".name", "the name " + quoteInput(spec.name) +
                                          " is used twice (bodies and particles share the names)");
      }
      const auto added = world.addBody(spec);
      if (!added) throw ParamError(k, added.message());
    }
  }
}

void readJoints(XmlRpcValue& list, const std::string& key, engine::World& world,
                const BodyLimits& limits, JointNames& names) {
  requireArray(list, key);
  for (int i = 0; i < list.size(); ++i) {
    const std::string k = indexed(key, i);
    XmlRpcValue& j = list[i];
    requireStruct(j, k);
    JointRequest request;
    request.type = stringOr(j, k, "type", "");
    const auto fields = jointFields(request.type);
    if (!fields) {
      throw ParamError(k + ".type", "unknown joint type " + quoteInput(request.type) +
                                        " (known: " + jointTypeNames() + ")");
    }
    std::vector<std::string> allowed{
        "type", "name", "a", "b", "anchor", "anchor_b", "collide_connected"};
    for (const JointField& field : *fields) allowed.push_back(field.name);
    checkKeys(j, k, allowed);
    if (world.joints().size() >= limits.max_joints) {
      throw ParamError(k, "the scene has more than ~max_joints (" +
                              std::to_string(limits.max_joints) + ") joints");
    }
    request.name = stringOr(j, k, "name", "");
    if (!request.name.empty()) throwIfBad(checkJointName(request.name, names), k);
    const std::string a = stringOr(j, k, "a", "");
    if (a.empty()) throw ParamError(k + ".a", "is required (a body or particle name)");
    request.a = endNamed(world, a, k + ".a");
    request.b = endNamed(world, stringOr(j, k, "b", ""), k + ".b");
    if (!has(j, "anchor")) throw ParamError(k + ".anchor", "is required (a world point)");
    request.anchor_a = readVec3(j["anchor"], k + ".anchor");
    request.anchor_b = vec3Or(j, k, "anchor_b", request.anchor_a);
    request.collide_connected = boolOr(j, k, "collide_connected", false);
    for (const JointField& field : *fields) {
      if (!has(j, field.name)) continue;
      const std::string fk = k + "." + field.name;
      switch (field.meaning) {
        case JointFieldMeaning::kDirection:
          request.values.directions[field.name] = readVec3(j[field.name], fk);
          break;
        case JointFieldMeaning::kFlag:
          request.values.flags[field.name] = readBool(j[field.name], fk);
          break;
        default:
          request.values.numbers[field.name] = readReal(j[field.name], fk);
          break;
      }
    }
    const auto added = addJoint(world, request);
    if (!added) throwIfBad(added.status(), k);
    if (!request.name.empty()) names[*added] = request.name;
  }
}

namespace {

// Where an end sits when the scene does not say: a body's origin, the particle; the world needs a
// point.
Vec3 defaultAnchor(const engine::World& world, const JointEndRef& end, const std::string& key) {
  switch (end.kind) {
    case JointEndRef::Kind::kBody:
      return world.bodies()
          .pose(*world.bodies().find(*world.bodies().findByName(end.name)))
          .position;
    case JointEndRef::Kind::kParticle:
      return world.particles().positions().col(static_cast<Eigen::Index>(
          *world.particles().find(*world.particles().findByName(end.name))));
    case JointEndRef::Kind::kWorld:
      break;
  }
  throw ParamError(key, "is required for an end in the world");
}

}  // namespace

void readPointSpring(XmlRpcValue& s, const std::string& k, engine::World& world) {
  checkKeys(s, k, {"type", "a", "b", "anchor", "anchor_b", "stiffness", "rest_length", "damping"});
  const std::string type = stringOr(s, k, "type", "");
  const std::string a = stringOr(s, k, "a", "");
  if (a.empty()) throw ParamError(k + ".a", "is required (a body or particle name)");
  const JointEndRef end_a = endNamed(world, a, k + ".a");
  const JointEndRef end_b = endNamed(world, stringOr(s, k, "b", ""), k + ".b");
  const Vec3 anchor_a = has(s, "anchor") ? readVec3(s["anchor"], k + ".anchor")
                                         : defaultAnchor(world, end_a, k + ".anchor");
  const Vec3 anchor_b = has(s, "anchor_b") ? readVec3(s["anchor_b"], k + ".anchor_b")
                                           : defaultAnchor(world, end_b, k + ".anchor_b");
  BodySpringRequest request;
  request.pull_only = type == "bungee";
  request.a = end_a;
  request.b = end_b;
  request.anchor_a = anchor_a;
  request.anchor_b = anchor_b;
  request.stiffness = realOr(s, k, "stiffness", 0.0);
  request.damping = realOr(s, k, "damping", 0.0);
  request.rest_length = realOr(s, k, "rest_length", -1.0);
  if (has(s, "rest_length") && request.rest_length < 0.0) {
    throw ParamError(k + ".rest_length", "must be >= 0 (left out: the distance)");
  }
  const auto added = addBodySpring(world, request);
  if (!added) throw ParamError(k, added.message());
}

std::vector<engine::BodyId> readBodyTargets(XmlRpcValue& s, const std::string& k,
                                            const engine::World& world) {
  XmlRpcValue& names = s["bodies"];
  requireArray(names, k + ".bodies");
  std::vector<engine::BodyId> ids;
  for (int j = 0; j < names.size(); ++j) {
    const std::string name = readString(names[j], indexed(k + ".bodies", j));
    const auto id = world.bodies().findByName(name);
    if (!id) throw ParamError(indexed(k + ".bodies", j), "no body named " + quoteInput(name));
    ids.push_back(*id);
  }
  return ids;
}

}  // namespace node
}  // namespace mass_aggregate_sim
