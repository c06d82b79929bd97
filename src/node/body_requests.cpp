#include "mass_aggregate_sim/node/body_requests.h"

#include <cmath>
#include <sstream>
#include <type_traits>
#include <variant>

#include "mass_aggregate_sim/engine/bodies/mass_properties.h"
#include "mass_aggregate_sim/node/input_limits.h"

namespace mass_aggregate_sim {
namespace node {

using engine::Quat;
using engine::Real;
using engine::Result;
using engine::Status;
using engine::Transform;
using engine::Vec3;

namespace {

std::string number(const Real value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

Status inRange(const Real value, const Real low, const Real high, const std::string& field,
               const char* unit) {
  if (!std::isfinite(value)) return Status::error(field + ": must be finite");
  if (value < low || value > high) {
    return Status::error(field + ": must be in [" + number(low) + ", " + number(high) + "] " +
                         unit + ", got " + number(value));
  }
  return Status::ok();
}

// Checks every size a shape kind declares (BodyShapeKind<K>::fields) against the node's bounds.
class SizeCheck {
 public:
  explicit SizeCheck(std::string where) : where_(std::move(where)) {}
  Status status = Status::ok();
  void length(const char* name, const Real& value) {
    keep(inRange(value, kMinBodySize, kMaxBodySize, where_ + name, "m"));
  }
  void extents(const char* name, const Vec3& value) {
    for (int axis = 0; axis < 3; ++axis) {
      keep(inRange(value[axis], kMinBodySize, kMaxBodySize,
                   where_ + name + "[" + std::to_string(axis) + "]", "m"));
    }
  }

 private:
  void keep(const Status& s) {
    if (status && !s) status = s;
  }
  std::string where_;
};

Status checkShape(const engine::BodyShapeSpec& shape, const std::string& where) {
  SizeCheck sizes(where);
  std::visit(
      [&](const auto& geometry) {
        auto copy = geometry;
        engine::BodyShapeKind<std::decay_t<decltype(geometry)>>::fields(copy, sizes);
      },
      shape.geometry);
  if (!sizes.status) return sizes.status;
  Status valid = checkVector(shape.local.position, kMaxBodySize, where + "position", "m");
  if (valid) valid = checkUnitQuaternion(shape.local.rotation, where + "orientation");
  if (valid) valid = inRange(shape.density, kMinDensity, kMaxDensity, where + "density", "kg/m^3");
  if (valid) valid = inRange(shape.material.friction, 0.0, kMaxFriction, where + "friction", "");
  if (valid) valid = inRange(shape.material.restitution, 0.0, 1.0, where + "restitution", "");
  return valid;
}

}  // namespace

Result<engine::BodyId> resolveBody(const engine::World& world, const BodyRef& ref) {
  if (!ref.name.empty()) {
    const auto id = world.bodies().findByName(ref.name);
    if (!id) return Status::error("no body named " + quoteInput(ref.name));
    return *id;
  }
  const engine::BodyId id = engine::BodyId::fromPacked(ref.id);
  if (!world.bodies().contains(id)) {
    return Status::error("no body with id " + std::to_string(ref.id) + " (" +
                         world.bodies().describeInvalid(id) + ")");
  }
  return id;
}

Twist bodyTwist(const engine::BodyStore& bodies, const std::size_t dense) {
  const Vec3 origin = bodies.pose(dense).position;
  return Twist{bodies.velocityAt(dense, origin), bodies.angularVelocity(dense)};
}

Vec3 centreVelocity(const Transform& pose, const Transform& mass_frame, const Twist& twist) {
  const Vec3 centre = pose.apply(mass_frame.position);
  return twist.linear + twist.angular.cross(centre - pose.position);
}

void setSpecTwist(engine::BodySpec& spec, const Twist& twist) {
  spec.linear_velocity = twist.linear;
  spec.angular_velocity = twist.angular;
  if (!spec.pose.position.allFinite() || !spec.pose.rotation.coeffs().allFinite()) return;
  const Result<engine::MassProperties> props =
      engine::computeMassProperties(spec.shapes, spec.mass);
  if (!props) return;
  Transform pose = spec.pose;
  pose.rotation.normalize();
  spec.linear_velocity = centreVelocity(pose, props.value().frame, twist);
}

ReferenceFrame bodyFrame(const engine::BodyStore& bodies, const std::size_t dense) {
  return ReferenceFrame{bodies.pose(dense), bodyTwist(bodies, dense)};
}

Transform poseToWorld(const ReferenceFrame& frame, const Transform& local) {
  return frame.pose * local;
}

Transform poseInFrame(const ReferenceFrame& frame, const Transform& world) {
  return frame.pose.inverse() * world;
}

Twist twistToWorld(const ReferenceFrame& frame, const Vec3& origin, const Twist& relative) {
  const Quat& r = frame.pose.rotation;
  const Twist& f = frame.twist;
  Twist out;
  out.angular = r * relative.angular + f.angular;
  out.linear = r * relative.linear + f.linear + f.angular.cross(origin - frame.pose.position);
  return out;
}

Twist twistInFrame(const ReferenceFrame& frame, const Vec3& origin, const Twist& world) {
  const Quat inverse = frame.pose.rotation.conjugate();
  const Twist& f = frame.twist;
  Twist out;
  out.angular = inverse * (world.angular - f.angular);
  out.linear = inverse * (world.linear - f.linear - f.angular.cross(origin - frame.pose.position));
  return out;
}

Status checkUnitQuaternion(const Quat& q, const std::string& field) {
  if (!q.coeffs().allFinite()) return Status::error(field + ": must be finite");
  const Real norm = q.norm();
  if (std::abs(norm - 1.0) > kUnitQuaternionTolerance) {
    return Status::error(field + ": must be a unit quaternion (|q| within " +
                         number(kUnitQuaternionTolerance) + " of 1), got |q| = " + number(norm) +
                         (norm == 0.0 ? " (the identity is w: 1)" : ""));
  }
  return Status::ok();
}

Status checkBodySpec(const engine::BodySpec& spec, const std::string& world_frame) {
  if (!spec.name.empty()) {
    const Status name = checkParticleName(spec.name, world_frame);
    if (!name) return name;
  }
  Status valid = checkPosition(spec.pose.position, "pose.position");
  if (valid) valid = checkUnitQuaternion(spec.pose.rotation, "pose.orientation");
  if (valid) valid = checkVelocity(spec.linear_velocity, "twist.linear");
  if (valid) {
    valid = checkVector(spec.angular_velocity, kMaxAngularSpeed, "twist.angular", "rad/s");
  }
  if (valid) {
    valid = inRange(spec.linear_damping, 0.0, kMaxBodyDamping, "linear_damping", "1/s");
  }
  if (valid) {
    valid = inRange(spec.angular_damping, 0.0, kMaxBodyDamping, "angular_damping", "1/s");
  }
  if (!valid) return valid;
  if (spec.type == engine::BodyType::kFixed &&
      !(spec.linear_velocity.isZero(0.0) && spec.angular_velocity.isZero(0.0))) {
    return Status::error("twist: a fixed body cannot have a velocity");
  }
  if (spec.shapes.empty()) return Status::error("shapes: a body needs at least one shape");
  if (spec.shapes.size() > kMaxShapesPerBody) {
    return Status::error("shapes: at most " + std::to_string(kMaxShapesPerBody) +
                         " per body, got " + std::to_string(spec.shapes.size()));
  }
  for (std::size_t k = 0; k < spec.shapes.size(); ++k) {
    const Status shape = checkShape(spec.shapes[k], "shapes[" + std::to_string(k) + "].");
    if (!shape) return shape;
  }
  if (spec.mass != 0.0) {
    const Status mass =
        inRange(spec.mass, kMinMass, kMaxMass, "mass", "kg (or 0: from the shapes)");
    if (!mass) return mass;
  }
  const Result<engine::MassProperties> props =
      engine::computeMassProperties(spec.shapes, spec.mass);
  if (!props) return Status::error("shapes: " + props.message());
  const engine::MassProperties& m = *props;
  if (!(m.mass >= kMinMass && m.mass <= kMaxMass)) {
    return Status::error("shapes: their mass " + number(m.mass) + " kg is outside [" +
                         number(kMinMass) + ", " + number(kMaxMass) +
                         "] kg (set mass, or change the densities)");
  }
  const Real largest = m.principal_inertia.maxCoeff();
  const Real smallest = m.principal_inertia.minCoeff();
  if (!(smallest > 0.0) || smallest < kMinInertiaRatio * largest) {
    return Status::error("shapes: the inertia is singular: principal moments " +
                         number(m.principal_inertia.x()) + ", " + number(m.principal_inertia.y()) +
                         ", " + number(m.principal_inertia.z()) + " kg m^2, the smallest below " +
                         number(kMinInertiaRatio) + " of the largest");
  }
  return Status::ok();
}

std::string bodyShapeNames() {
  std::string names;
  engine::forEachKind(engine::BodyShapeKinds{}, [&](const auto tag) {
    using Shape = typename decltype(tag)::type;
    names += (names.empty() ? "" : ", ") + std::string(engine::BodyShapeKind<Shape>::kName);
  });
  return names;
}

const char* bodyTypeName(const engine::BodyType type) {
  switch (type) {
    case engine::BodyType::kDynamic:
      return "dynamic";
    case engine::BodyType::kKinematic:
      return "kinematic";
    case engine::BodyType::kFixed:
      return "fixed";
  }
  return "unknown";
}

std::optional<engine::BodyType> parseBodyType(const std::string& name) {
  for (const auto type :
       {engine::BodyType::kDynamic, engine::BodyType::kKinematic, engine::BodyType::kFixed}) {
    if (name == bodyTypeName(type)) return type;
  }
  return std::nullopt;
}

}  // namespace node
}  // namespace mass_aggregate_sim
