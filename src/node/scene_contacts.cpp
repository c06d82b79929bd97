#include "mass_aggregate_sim/node/scene_contacts.h"

#include <Eigen/Geometry>
#include <cmath>
#include <string>
#include <vector>

#include "mass_aggregate_sim/node/input_limits.h"
#include "mass_aggregate_sim/node/xmlrpc_reader.h"

namespace mass_aggregate_sim {
namespace node {
namespace {

using XmlRpc::XmlRpcValue;

std::string indexed(const std::string& key, const int i) {
  return key + "[" + std::to_string(i) + "]";
}

}  // namespace

void readCollisionSettings(XmlRpcValue& s, const std::string& k, engine::World& world) {
  checkKeys(s, k,
            {"particle_collisions", "broadphase", "continuous", "particle_restitution",
             "particle_friction", "max_iterations", "penetration_slop", "collide_linked",
             "rod_tolerance", "velocity_tolerance", "max_contacts", "runaway_speed"});
  engine::CollisionSettings c = world.collisionSettings();
  c.particle_collisions = boolOr(s, k, "particle_collisions", c.particle_collisions);
  if (has(s, "broadphase")) {
    const std::string name = readString(s["broadphase"], k + ".broadphase");
    const auto parsed = engine::parseBroadphase(name);
    if (!parsed) {
      throw ParamError(k + ".broadphase", "unknown broadphase " + quoteInput(name) +
                                              " (known: " + engine::broadphaseNames() + ")");
    }
    c.broadphase = *parsed;
  }
  c.continuous = boolOr(s, k, "continuous", c.continuous);
  c.particle_restitution = realOr(s, k, "particle_restitution", c.particle_restitution);
  c.particle_friction = realOr(s, k, "particle_friction", c.particle_friction);
  c.max_iterations = intOr(s, k, "max_iterations", c.max_iterations);
  c.penetration_slop = realOr(s, k, "penetration_slop", c.penetration_slop);
  c.collide_linked = boolOr(s, k, "collide_linked", c.collide_linked);
  c.rod_tolerance = realOr(s, k, "rod_tolerance", c.rod_tolerance);
  c.velocity_tolerance = realOr(s, k, "velocity_tolerance", c.velocity_tolerance);
  c.runaway_speed = realOr(s, k, "runaway_speed", c.runaway_speed);
  const int max_contacts = intOr(s, k, "max_contacts", static_cast<int>(c.max_contacts));
  if (max_contacts < 0) throw ParamError(k + ".max_contacts", "must be >= 0 (0: no limit)");
  c.max_contacts = static_cast<std::size_t>(max_contacts);
  const engine::Status valid = world.setCollisionSettings(c);
  if (!valid) throw ParamError(k, valid.message());
}

namespace {

using engine::Real;
using engine::Vec3;

// The names of a collider kind's fields (ShapeKind::fields), for the key check.
class FieldNames {
 public:
  std::vector<std::string> names{"type", "restitution", "friction"};
  void point(const char* name, const Vec3&) { names.emplace_back(name); }
  void direction(const char* name, const Vec3&) { names.emplace_back(name); }
  void coordinate(const char* name, const Real&) { names.emplace_back(name); }
  void length(const char* name, const Real&) { names.emplace_back(name); }
  void extents(const char* name, const Vec3&) { names.emplace_back(name); }
  void orientation(const char* name, const Eigen::Quaterniond&) { names.emplace_back(name); }
};

// Reads a collider kind's fields from its scene entry by what they mean, each within the node's
// bounds (kept in `bounds`, reported after the engine's own checks, which name the rule first).
class FieldReader {
 public:
  FieldReader(XmlRpcValue& entry, const std::string& key) : entry_(entry), key_(key) {}
  engine::Status bounds = engine::Status::ok();

  void point(const char* name, Vec3& value) {
    value = vec3Or(entry_, key_, name, value);
    keep(checkPosition(value, name));
  }
  void direction(const char* name, Vec3& value) { value = vec3Or(entry_, key_, name, value); }
  void coordinate(const char* name, Real& value) {
    value = realOr(entry_, key_, name, value);
    keep(checkNonNegative(std::abs(value), kMaxCoordinate, name, "m (absolute)"));
  }
  void length(const char* name, Real& value) {
    value = realOr(entry_, key_, name, value);
    keep(checkNonNegative(value, kMaxLength, name, "m"));
  }
  void extents(const char* name, Vec3& value) {
    value = vec3Or(entry_, key_, name, value);
    keep(checkVector(value, kMaxLength, name, "m"));
  }
  void orientation(const char* name, Eigen::Quaterniond& value) {
    if (!has(entry_, name)) return;
    // [x, y, z, w], as in geometry_msgs/Quaternion.
    XmlRpcValue& q = entry_[name];
    const std::string qk = key_ + "." + name;
    requireArray(q, qk);
    if (q.size() != 4) throw ParamError(qk, "expected a quaternion [x, y, z, w]");
    value = Eigen::Quaterniond(readReal(q[3], indexed(qk, 3)), readReal(q[0], indexed(qk, 0)),
                               readReal(q[1], indexed(qk, 1)), readReal(q[2], indexed(qk, 2)));
  }

 private:
  void keep(const engine::Status& status) {
    if (bounds && !status) bounds = status;
  }
  XmlRpcValue& entry_;
  std::string key_;
};

}  // namespace

void readColliders(XmlRpcValue& list, const std::string& key, engine::World& world) {
  requireArray(list, key);
  std::string known;
  engine::forEachKind(engine::ShapeKinds{}, [&](const auto tag) {
    using Shape = typename decltype(tag)::type;
    known += (known.empty() ? "" : ", ") + std::string(engine::ShapeKind<Shape>::kName);
  });
  for (int i = 0; i < list.size(); ++i) {
    const std::string k = indexed(key, i);
    XmlRpcValue& c = list[i];
    const std::string type = stringOr(c, k, "type", "");
    bool matched = false;
    // Every collider kind the engine has, read through the fields it declares.
    engine::forEachKind(engine::ShapeKinds{}, [&](const auto tag) {
      using Shape = typename decltype(tag)::type;
      if (matched || type != engine::ShapeKind<Shape>::kName) return;
      matched = true;
      Shape shape;
      FieldNames names;
      engine::ShapeKind<Shape>::fields(shape, names);
      checkKeys(c, k, names.names);
      shape.material.restitution = realOr(c, k, "restitution", shape.material.restitution);
      shape.material.friction = realOr(c, k, "friction", shape.material.friction);
      FieldReader reader(c, k);
      engine::ShapeKind<Shape>::fields(shape, reader);
      const engine::Result<engine::ColliderId> added = world.addCollider(shape);
      if (!added) throw ParamError(k, added.message());
      throwIfBad(reader.bounds, k);
    });
    if (!matched) {
      throw ParamError(k + ".type",
                       "unknown collider " + quoteInput(type) + " (known: " + known + ")");
    }
  }
}

}  // namespace node
}  // namespace mass_aggregate_sim
