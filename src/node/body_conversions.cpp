#include "mass_aggregate_sim/node/body_conversions.h"

#include <unordered_map>

#include "mass_aggregate_sim/node/conversions.h"
#include "mass_aggregate_sim/node/input_limits.h"

namespace mass_aggregate_sim {
namespace node {
namespace {

using engine::Real;
using engine::Result;
using engine::Status;
using engine::Vec3;

// Reads a body shape kind's fields (BodyShapeKind<K>::fields) from the message fields of the same
// name; a field the message lacks is refused.
class ShapeMsgReader {
 public:
  explicit ShapeMsgReader(const BodyShapeSpec& msg) : msg_(msg) {}
  Status status = Status::ok();
  void length(const char* name, Real& value) {
    const std::string field = name;
    if (field == "radius") {
      value = msg_.radius;
    } else if (field == "half_length") {
      value = msg_.half_length;
    } else {
      missing(field);
    }
  }
  void extents(const char* name, Vec3& value) {
    if (std::string(name) == "half_extents") {
      value = fromMsg(msg_.half_extents);
    } else {
      missing(name);
    }
  }

 private:
  void missing(const std::string& field) {
    if (status) status = Status::error(field + ": BodyShapeSpec has no such field");
  }
  const BodyShapeSpec& msg_;
};

}  // namespace

engine::Transform fromMsg(const geometry_msgs::Pose& pose) {
  const auto& q = pose.orientation;
  return engine::Transform{Vec3(pose.position.x, pose.position.y, pose.position.z),
                           engine::Quat(q.w, q.x, q.y, q.z)};
}

geometry_msgs::Pose toPoseMsg(const engine::Transform& pose) {
  geometry_msgs::Pose msg;
  msg.position = toPointMsg(pose.position);
  msg.orientation.x = pose.rotation.x();
  msg.orientation.y = pose.rotation.y();
  msg.orientation.z = pose.rotation.z();
  msg.orientation.w = pose.rotation.w();
  return msg;
}

Twist fromMsg(const geometry_msgs::Twist& twist) {
  return Twist{fromMsg(twist.linear), fromMsg(twist.angular)};
}

geometry_msgs::Twist toTwistMsg(const Twist& twist) {
  geometry_msgs::Twist msg;
  msg.linear = toVector3Msg(twist.linear);
  msg.angular = toVector3Msg(twist.angular);
  return msg;
}

Result<engine::BodySpec> toBodySpec(const BodySpec& msg) {
  engine::BodySpec spec;
  switch (msg.type) {
    case BodySpec::DYNAMIC:
      spec.type = engine::BodyType::kDynamic;
      break;
    case BodySpec::KINEMATIC:
      spec.type = engine::BodyType::kKinematic;
      break;
    case BodySpec::FIXED:
      spec.type = engine::BodyType::kFixed;
      break;
    default:
      return Status::error("type: must be DYNAMIC (0), KINEMATIC (1) or FIXED (2), got " +
                           std::to_string(msg.type));
  }
  spec.name = msg.name;
  spec.pose = fromMsg(msg.pose);
  spec.mass = msg.mass;
  spec.linear_damping = msg.linear_damping;
  spec.angular_damping = msg.angular_damping;
  spec.can_sleep = !msg.never_sleep;
  if (msg.shapes.size() > kMaxShapesPerBody) {
    return Status::error("shapes: at most " + std::to_string(kMaxShapesPerBody) +
                         " per body, got " + std::to_string(msg.shapes.size()));
  }
  for (std::size_t k = 0; k < msg.shapes.size(); ++k) {
    const BodyShapeSpec& s = msg.shapes[k];
    const std::string where = "shapes[" + std::to_string(k) + "].";
    ShapeMsgReader reader(s);
    const auto geometry = readBodyShape(s.type, reader);
    if (!geometry) {
      return Status::error(where + "type: unknown shape " + quoteInput(s.type) +
                           " (known: " + bodyShapeNames() + ")");
    }
    if (!reader.status) return Status::error(where + reader.status.message());
    engine::BodyShapeSpec shape;
    shape.geometry = *geometry;
    shape.local = fromMsg(s.pose);
    shape.density = s.density == 0.0 ? 1000.0 : s.density;
    shape.material.friction = s.friction;
    shape.material.restitution = s.restitution;
    spec.shapes.push_back(shape);
  }
  return spec;
}

Result<JointEndRef> toJointEnd(const JointEndSpec& msg, const char* field) {
  JointEndRef end;
  switch (msg.kind) {
    case JointEndSpec::WORLD:
      end.kind = JointEndRef::Kind::kWorld;
      return end;
    case JointEndSpec::BODY:
      end.kind = JointEndRef::Kind::kBody;
      break;
    case JointEndSpec::PARTICLE:
      end.kind = JointEndRef::Kind::kParticle;
      break;
    default:
      return Status::error(std::string(field) +
                           ".kind: must be WORLD (0), BODY (1) or PARTICLE (2), got " +
                           std::to_string(msg.kind));
  }
  end.id = msg.id;
  end.name = msg.name;
  return end;
}

namespace {

// A request's two ends, from the message's a and b.
template <typename Message, typename Request>
Status readEnds(const Message& msg, Request& request) {
  const auto a = toJointEnd(msg.a, "a");
  if (!a) return a.status();
  const auto b = toJointEnd(msg.b, "b");
  if (!b) return b.status();
  request.a = *a;
  request.b = *b;
  return Status::ok();
}

}  // namespace

Result<JointRequest> toJointRequest(const AddJoint::Request& msg) {
  JointRequest request;
  request.type = msg.type;
  request.name = msg.name;
  const Status ends = readEnds(msg, request);
  if (!ends) return ends;
  request.anchor_a = fromMsg(msg.anchor);
  request.anchor_b = msg.separate_anchor_b ? fromMsg(msg.anchor_b) : request.anchor_a;
  request.collide_connected = msg.collide_connected;
  request.every_field = true;
  JointValues& v = request.values;
  v.directions["axis"] = fromMsg(msg.axis);
  v.flags["limit"] = msg.limit;
  v.flags["motor"] = msg.motor;
  v.numbers["lower"] = msg.lower;
  v.numbers["upper"] = msg.upper;
  v.numbers["motor_speed"] = msg.motor_speed;
  v.numbers["max_motor_torque"] = msg.max_motor_torque;
  v.numbers["min_length"] = msg.min_length;
  v.numbers["max_length"] = msg.max_length;
  return request;
}

void placeJointRequest(const ReferenceFrame& frame, JointRequest& request, AddJoint::Request& msg) {
  request.anchor_a = frame.pose.apply(request.anchor_a);
  request.anchor_b = frame.pose.apply(request.anchor_b);
  for (auto& [name, direction] : request.values.directions) {
    direction = frame.pose.rotation * direction;
  }
  msg.frame_id.clear();
  msg.anchor = toPointMsg(request.anchor_a);
  if (msg.separate_anchor_b) msg.anchor_b = toPointMsg(request.anchor_b);
  msg.axis = toVector3Msg(request.values.directions["axis"]);
}

Result<BodySpringRequest> toBodySpringRequest(const AddBodySpring::Request& msg) {
  BodySpringRequest request;
  const auto pull_only = parseBodySpringType(msg.type);
  if (!pull_only) return pull_only.status();
  request.pull_only = *pull_only;
  const Status ends = readEnds(msg, request);
  if (!ends) return ends;
  request.anchor_a = fromMsg(msg.anchor);
  request.anchor_b = fromMsg(msg.anchor_b);
  request.stiffness = msg.stiffness;
  request.damping = msg.damping;
  request.rest_length = msg.rest_length;
  return request;
}

void placeBodySpringRequest(const ReferenceFrame& frame, BodySpringRequest& request,
                            AddBodySpring::Request& msg) {
  request.anchor_a = frame.pose.apply(request.anchor_a);
  request.anchor_b = frame.pose.apply(request.anchor_b);
  msg.frame_id.clear();
  msg.anchor = toPointMsg(request.anchor_a);
  msg.anchor_b = toPointMsg(request.anchor_b);
}

void fillBodyArray(const BodySnapshot& bodies, const std::uint64_t step, const double time,
                   BodyArray& msg) {
  const std::size_t n = bodies.ids.size();
  msg.step = step;
  msg.time = time;
  msg.bodies.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    Body& b = msg.bodies[i];
    b.id = bodies.ids[i];
    b.name = bodies.names[i];
    b.type = bodies.types[i] == engine::BodyType::kDynamic     ? BodySpec::DYNAMIC
             : bodies.types[i] == engine::BodyType::kKinematic ? BodySpec::KINEMATIC
                                                               : BodySpec::FIXED;
    b.pose = toPoseMsg(bodies.poses[i]);
    b.twist = toTwistMsg(bodies.twists[i]);
    b.sleeping = bodies.sleeping[i] != 0;
    b.mass = bodies.masses[i];
  }
}

void fillContacts(const BodySnapshot& bodies, const std::vector<std::uint64_t>& particle_ids,
                  const std::vector<std::string>& particle_names, const std::uint64_t step,
                  const double time, BodyContactArray& msg) {
  std::unordered_map<std::uint64_t, std::size_t> body_index;
  for (std::size_t i = 0; i < bodies.ids.size(); ++i) body_index[bodies.ids[i]] = i;
  std::unordered_map<std::uint64_t, std::size_t> particle_index;
  const auto body_name = [&](const std::uint64_t id) -> std::string {
    const auto it = body_index.find(id);
    return it == body_index.end() ? std::string() : bodies.names[it->second];
  };
  msg.step = step;
  msg.time = time;
  msg.contacts.clear();
  msg.contacts.reserve(bodies.contacts.size());
  for (const engine::BodyContactReport& report : bodies.contacts) {
    BodyContact c;
    c.body = report.body.packed();
    c.body_name = body_name(c.body);
    switch (report.other) {
      case engine::BodyContactReport::Other::kBody:
        c.other_kind = BodyContact::BODY;
        c.other = report.other_body.packed();
        c.other_name = body_name(c.other);
        break;
      case engine::BodyContactReport::Other::kCollider:
        c.other_kind = BodyContact::COLLIDER;
        c.other = report.collider;
        break;
      case engine::BodyContactReport::Other::kParticle:
        c.other_kind = BodyContact::PARTICLE;
        c.other = report.particle.packed();
        if (particle_index.empty()) {
          for (std::size_t i = 0; i < particle_ids.size(); ++i) particle_index[particle_ids[i]] = i;
        }
        if (const auto it = particle_index.find(c.other); it != particle_index.end()) {
          c.other_name = particle_names[it->second];
        }
        break;
    }
    c.normal = toVector3Msg(report.normal);
    for (const auto& point : report.points) {
      ContactPoint p;
      p.position = toPointMsg(point.position);
      p.depth = -point.separation;
      p.normal_impulse = point.normal_impulse;
      p.friction_impulse = toVector3Msg(point.friction_impulse);
      p.normal_force = bodies.substep > 0.0 ? point.normal_impulse / bodies.substep : 0.0;
      c.points.push_back(p);
    }
    msg.contacts.push_back(std::move(c));
  }
}

void fillJointStates(const BodySnapshot& bodies, sensor_msgs::JointState& msg) {
  const std::size_t n = bodies.hinges.size();
  msg.name.resize(n);
  msg.position.resize(n);
  msg.velocity.resize(n);
  msg.effort.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    msg.name[i] = bodies.hinges[i].name;
    msg.position[i] = bodies.hinges[i].position;
    msg.velocity[i] = bodies.hinges[i].velocity;
    msg.effort[i] = bodies.hinges[i].effort;
  }
}

}  // namespace node
}  // namespace mass_aggregate_sim
