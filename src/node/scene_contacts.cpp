#include "mass_aggregate_sim/node/scene_contacts.h"

#include <Eigen/Geometry>
#include <cmath>
#include <string>

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
             "rod_tolerance", "velocity_tolerance", "max_contacts"});
  engine::CollisionSettings c = world.collisionSettings();
  c.particle_collisions = boolOr(s, k, "particle_collisions", c.particle_collisions);
  if (has(s, "broadphase")) {
    const std::string name = readString(s["broadphase"], k + ".broadphase");
    const auto parsed = engine::parseBroadphase(name);
    if (!parsed) {
      throw ParamError(k + ".broadphase", "unknown broadphase '" + name +
                                              "' (known: " + engine::broadphaseNames() + ")");
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
  const int max_contacts = intOr(s, k, "max_contacts", static_cast<int>(c.max_contacts));
  if (max_contacts < 0) throw ParamError(k + ".max_contacts", "must be >= 0 (0: no limit)");
  c.max_contacts = static_cast<std::size_t>(max_contacts);
  const engine::Status valid = world.setCollisionSettings(c);
  if (!valid) throw ParamError(k, valid.message());
}

void readColliders(XmlRpcValue& list, const std::string& key, engine::World& world) {
  requireArray(list, key);
  for (int i = 0; i < list.size(); ++i) {
    const std::string k = indexed(key, i);
    XmlRpcValue& c = list[i];
    const std::string type = stringOr(c, k, "type", "");
    engine::Material material;
    material.restitution = realOr(c, k, "restitution", material.restitution);
    material.friction = realOr(c, k, "friction", material.friction);
    engine::Result<engine::ColliderId> added = engine::Status::error("unknown collider");
    // The node's bounds, reported after the engine's own checks (which name the rule first).
    engine::Status bounds = engine::Status::ok();
    if (type == "plane") {
      checkKeys(c, k, {"type", "normal", "offset", "restitution", "friction"});
      engine::PlaneCollider plane;
      plane.normal = vec3Or(c, k, "normal", plane.normal);
      plane.offset = realOr(c, k, "offset", plane.offset);
      bounds = checkNonNegative(std::abs(plane.offset), kMaxCoordinate, "offset", "m (absolute)");
      plane.material = material;
      added = world.addPlane(plane);
    } else if (type == "sphere") {
      checkKeys(c, k, {"type", "center", "radius", "restitution", "friction"});
      engine::SphereCollider sphere;
      sphere.center = vec3Or(c, k, "center", sphere.center);
      sphere.radius = realOr(c, k, "radius", sphere.radius);
      bounds = checkPosition(sphere.center, "center");
      if (bounds) bounds = checkNonNegative(sphere.radius, kMaxLength, "radius", "m");
      sphere.material = material;
      added = world.addSphere(sphere);
    } else if (type == "box") {
      checkKeys(c, k, {"type", "center", "half_extents", "orientation", "restitution", "friction"});
      engine::BoxCollider box;
      box.center = vec3Or(c, k, "center", box.center);
      box.half_extents = vec3Or(c, k, "half_extents", box.half_extents);
      bounds = checkPosition(box.center, "center");
      if (bounds) bounds = checkVector(box.half_extents, kMaxLength, "half_extents", "m");
      if (has(c, "orientation")) {
        // [x, y, z, w], as in geometry_msgs/Quaternion.
        XmlRpcValue& q = c["orientation"];
        const std::string qk = k + ".orientation";
        requireArray(q, qk);
        if (q.size() != 4) throw ParamError(qk, "expected a quaternion [x, y, z, w]");
        box.orientation =
            Eigen::Quaterniond(readReal(q[3], indexed(qk, 3)), readReal(q[0], indexed(qk, 0)),
                               readReal(q[1], indexed(qk, 1)), readReal(q[2], indexed(qk, 2)));
      }
      box.material = material;
      added = world.addBox(box);
    } else if (type == "capsule") {
      checkKeys(c, k, {"type", "a", "b", "radius", "restitution", "friction"});
      engine::CapsuleCollider capsule;
      capsule.a = vec3Or(c, k, "a", capsule.a);
      capsule.b = vec3Or(c, k, "b", capsule.b);
      capsule.radius = realOr(c, k, "radius", capsule.radius);
      bounds = checkPosition(capsule.a, "a");
      if (bounds) bounds = checkPosition(capsule.b, "b");
      if (bounds) bounds = checkNonNegative(capsule.radius, kMaxLength, "radius", "m");
      capsule.material = material;
      added = world.addCapsule(capsule);
    } else {
      throw ParamError(k + ".type",
                       "unknown collider '" + type + "' (known: plane, sphere, box, capsule)");
    }
    if (!added) throw ParamError(k, added.message());
    throwIfBad(bounds, k);
  }
}

}  // namespace node
}  // namespace mass_aggregate_sim
