// Simulation's requests on rigid bodies and joints: each checked in full before anything changes.
#include <algorithm>
#include <cmath>
#include <set>

#include "mass_aggregate_sim/node/input_limits.h"
#include "mass_aggregate_sim/node/simulation.h"

namespace mass_aggregate_sim {
namespace node {
namespace {

using engine::BodyId;
using engine::JointId;
using engine::Real;
using engine::Result;
using engine::Status;
using engine::Transform;
using engine::Vec3;

std::string nameOf(const engine::World& world, const BodyId id) {
  const auto dense = world.bodies().find(id);
  const std::string& name = dense ? world.bodies().name(*dense) : std::string();
  return name.empty() ? "body " + std::to_string(id.packed()) : "body " + quoteInput(name);
}

Status needsDynamic(const engine::World& world, const BodyId id, const char* what) {
  const std::size_t dense = *world.bodies().find(id);
  if (world.bodies().dynamic(dense)) return Status::ok();
  return Status::error(nameOf(world, id) + " is " + bodyTypeName(world.bodies().type(dense)) +
                       ": " + what + " cannot move it");
}

}  // namespace

Result<BodyId> Simulation::resolveBody(const BodyRef& ref) const {
  return node::resolveBody(world_, ref);
}

Result<std::vector<BodyId>> Simulation::spawnBodies(const std::vector<engine::BodySpec>& specs) {
  if (specs.empty()) return Status::error("no bodies to spawn");
  const std::size_t now = world_.bodies().size();
  if (specs.size() > limits_.max_bodies || now + specs.size() > limits_.max_bodies) {
    return Status::error("spawning " + std::to_string(specs.size()) + " bodies would make " +
                         std::to_string(now + specs.size()) + ", over ~max_bodies (" +
                         std::to_string(limits_.max_bodies) + ")");
  }
  std::set<std::string> names;
  for (std::size_t i = 0; i < specs.size(); ++i) {
    const std::string where = "bodies[" + std::to_string(i) + "].";
    const Status valid = checkBodySpec(specs[i], limits_.world_frame);
    if (!valid) return Status::error(where + valid.message());
    const std::string& name = specs[i].name;
    if (name.empty()) continue;
    if (world_.bodies().findByName(name) || world_.particles().findByName(name) ||
        !names.insert(name).second) {
      return Status::error(where + "name: " + quoteInput(name) +
                           " is already taken (bodies and particles share the tf names)");
    }
  }
  std::vector<BodyId> ids;
  ids.reserve(specs.size());
  for (std::size_t i = 0; i < specs.size(); ++i) {
    const auto id = world_.addBody(specs[i]);
    // checkBodySpec ran the engine's own checks (computeMassProperties) already.
    if (!id) {
      for (const BodyId added : ids) world_.removeBody(added);
      return Status::error("bodies[" + std::to_string(i) + "]: " + id.message());
    }
    ids.push_back(*id);
  }
  return ids;
}

Result<RemovedBodies> Simulation::removeBodies(const std::vector<BodyRef>& refs) {
  if (refs.empty()) return Status::error("no bodies to remove");
  if (refs.size() > limits_.max_bodies) {
    return Status::error("ids and names: " + std::to_string(refs.size()) +
                         " bodies named, more than ~max_bodies (" +
                         std::to_string(limits_.max_bodies) + ")");
  }
  RemovedBodies removed;
  std::set<BodyId> seen;
  for (const BodyRef& ref : refs) {
    const auto id = resolveBody(ref);
    if (!id) return id.status();
    if (!seen.insert(*id).second) {
      return Status::error("body " + std::to_string(id.value().packed()) + " is named twice");
    }
    removed.ids.push_back(*id);
  }
  const std::size_t joints_before = world_.joints().size();
  for (const BodyId id : removed.ids) {
    world_.removeBody(id);
    wrenches_.erase(std::remove_if(wrenches_.begin(), wrenches_.end(),
                                   [id](const SustainedWrench& w) { return w.body == id; }),
                    wrenches_.end());
  }
  removed.joints = joints_before - world_.joints().size();
  pruneJointNames(world_, joint_names_);
  return removed;
}

Status Simulation::setBodyState(const BodyRef& ref, const std::optional<Transform>& pose,
                                const std::optional<Twist>& twist) {
  if (!pose && !twist) return Status::error("neither pose nor twist to set");
  const auto id = resolveBody(ref);
  if (!id) return id.status();
  const std::size_t dense = *world_.bodies().find(*id);
  if (pose) {
    Status valid = checkPosition(pose->position, "pose.position");
    if (valid) valid = checkUnitQuaternion(pose->rotation, "pose.orientation");
    if (!valid) return valid;
  }
  Vec3 centre_velocity = Vec3::Zero();
  if (twist) {
    Status valid = checkVelocity(twist->linear, "twist.linear");
    if (valid) valid = checkVector(twist->angular, kMaxAngularSpeed, "twist.angular", "rad/s");
    if (!valid) return valid;
    if (world_.bodies().type(dense) == engine::BodyType::kFixed &&
        !(twist->linear.isZero(0.0) && twist->angular.isZero(0.0))) {
      return Status::error(nameOf(world_, *id) + " is fixed: its velocity stays zero");
    }
    const Transform at = pose ? *pose : world_.bodies().pose(dense);
    centre_velocity = centreVelocity(at, world_.bodies().massFrame(dense), *twist);
    valid = checkVelocity(centre_velocity, "twist: the centre of mass's velocity");
    if (!valid) return valid;
  }
  if (pose) {
    const Status set = world_.setBodyPose(*id, *pose);
    if (!set) return set;
  }
  if (twist) return world_.setBodyVelocity(*id, centre_velocity, twist->angular);
  return Status::ok();
}

Result<std::uint64_t> Simulation::applyBodyWrench(const WrenchRequest& request) {
  const auto id = resolveBody(request.body);
  if (!id) return id.status();
  if (request.mode == ForceMode::kClear) {
    const std::size_t before = wrenches_.size();
    wrenches_.erase(std::remove_if(wrenches_.begin(), wrenches_.end(),
                                   [&](const SustainedWrench& w) { return w.body == *id; }),
                    wrenches_.end());
    if (wrenches_.size() == before) {
      return Status::error(nameOf(world_, *id) + " has no sustained wrench to clear");
    }
    return std::uint64_t{0};
  }
  Status valid = checkVector(request.force, kMaxForce, "wrench.force", "N");
  if (valid) valid = checkVector(request.torque, kMaxTorque, "wrench.torque", "N m");
  if (valid) valid = checkPosition(request.point, "reference_point");
  if (valid) valid = needsDynamic(world_, *id, "a wrench");
  if (!valid) return valid;
  if (request.mode == ForceMode::kOneStep) {
    world_.addBodyForce(*id, request.force, request.point);
    world_.addBodyTorque(*id, request.torque);
    return std::uint64_t{1};
  }
  const auto steps = sustainedSteps(request.mode, request.duration);
  if (!steps) return steps.status();
  const std::size_t dense = *world_.bodies().find(*id);
  wrenches_.push_back(SustainedWrench{*id, request.force,
                                      world_.bodies().pose(dense).applyInverse(request.point),
                                      request.torque, *steps});
  return static_cast<std::uint64_t>(std::max<std::int64_t>(*steps, 0));
}

Result<Twist> Simulation::applyBodyImpulse(const BodyRef& ref, const Vec3& impulse,
                                           const Vec3& point, const Vec3& angular_impulse) {
  const auto id = resolveBody(ref);
  if (!id) return id.status();
  Status valid = checkVector(impulse, kMaxForce, "impulse", "N s");
  if (valid) valid = checkVector(angular_impulse, kMaxTorque, "angular_impulse", "N m s");
  if (valid) valid = checkPosition(point, "reference_point");
  if (valid) valid = needsDynamic(world_, *id, "an impulse");
  if (!valid) return valid;
  // The velocities it would give, checked before anything changes: the engine's own formulas
  // (dv = J / m, dw = R diag(1 / I) R^T ((p - c) x J + L)).
  const engine::BodyStore& bodies = world_.bodies();
  const std::size_t dense = *bodies.find(*id);
  const engine::Mat3 r = bodies.orientation(dense).toRotationMatrix();
  const engine::Mat3 inverse_inertia =
      r * bodies.inversePrincipalInertia(dense).asDiagonal() * r.transpose();
  const Vec3 v = bodies.linearVelocity(dense) + bodies.inverseMass(dense) * impulse;
  const Vec3 w =
      bodies.angularVelocity(dense) +
      inverse_inertia * ((point - bodies.position(dense)).cross(impulse) + angular_impulse);
  valid = checkVelocity(v, "impulse: the resulting velocity");
  if (valid) {
    valid = checkVector(w, kMaxAngularSpeed, "impulse: the resulting angular velocity", "rad/s");
  }
  if (!valid) return valid;
  const Status applied = world_.applyBodyImpulse(*id, impulse, point, angular_impulse);
  if (!applied) return applied;
  return bodyTwist(world_.bodies(), *world_.bodies().find(*id));
}

Result<JointId> Simulation::addJoint(const JointRequest& request) {
  if (world_.joints().size() >= limits_.max_joints) {
    return Status::error("already " + std::to_string(world_.joints().size()) +
                         " joints, ~max_joints (" + std::to_string(limits_.max_joints) + ")");
  }
  if (!request.name.empty()) {
    const Status name = checkJointName(request.name, joint_names_);
    if (!name) return name;
  }
  const auto id = node::addJoint(world_, request);
  if (!id) return id;
  if (!request.name.empty()) joint_names_[*id] = request.name;
  return id;
}

Status Simulation::removeJoint(const JointId id) {
  if (!hasJoint(world_, id)) return Status::error("no joint with id " + std::to_string(id));
  const Status removed = world_.removeJoint(id);
  if (removed) joint_names_.erase(id);
  return removed;
}

Status Simulation::setHingeMotor(const JointId id, const bool enabled, const Real speed,
                                 const Real max_torque) {
  if (!std::isfinite(speed) || std::abs(speed) > kMaxAngularSpeed) {
    return Status::error("speed: must be finite and within +-" +
                         std::to_string(static_cast<long>(kMaxAngularSpeed)) + " rad/s");
  }
  if (!std::isfinite(max_torque) || max_torque < 0.0 || max_torque > kMaxTorque) {
    return Status::error("max_torque: must be in [0, 1e+09] N m");
  }
  return world_.setHingeMotor(id, enabled, speed, max_torque);
}

void Simulation::applyWrenches() {
  for (auto& w : wrenches_) {
    const std::size_t dense = *world_.bodies().find(w.body);
    world_.addBodyForce(w.body, w.force, world_.bodies().pose(dense).apply(w.point));
    world_.addBodyTorque(w.body, w.torque);
    if (w.steps_left > 0) --w.steps_left;
  }
  wrenches_.erase(std::remove_if(wrenches_.begin(), wrenches_.end(),
                                 [](const SustainedWrench& w) { return w.steps_left == 0; }),
                  wrenches_.end());
}

}  // namespace node
}  // namespace mass_aggregate_sim
