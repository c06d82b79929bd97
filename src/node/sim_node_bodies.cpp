// The body service handlers of SimNode: each checks what it can on the spinner thread, then
// resolves its frame (a body's frame is read where it is current), applies and records the
// request as a job on the world thread.
#include "mass_aggregate_sim/node/body_conversions.h"
#include "mass_aggregate_sim/node/conversions.h"
#include "mass_aggregate_sim/node/input_limits.h"
#include "mass_aggregate_sim/node/sim_node.h"
#include "service_helpers.h"

namespace mass_aggregate_sim {
namespace node {
namespace {

using engine::Result;
using engine::Status;
using engine::Transform;
using engine::Vec3;

std::string nameOf(const BodyRef& ref) {
  return ref.name.empty() ? "body " + std::to_string(ref.id) : "body " + quoteInput(ref.name);
}

std::optional<ForceMode> forceMode(const std::uint8_t mode) {
  switch (mode) {
    case ApplyBodyWrench::Request::ONE_STEP:
      return ForceMode::kOneStep;
    case ApplyBodyWrench::Request::DURATION:
      return ForceMode::kDuration;
    case ApplyBodyWrench::Request::UNTIL_CLEARED:
      return ForceMode::kUntilCleared;
    case ApplyBodyWrench::Request::CLEAR:
      return ForceMode::kClear;
  }
  return std::nullopt;
}

}  // namespace

Result<ReferenceFrame> SimNode::referenceFrame(const std::string& frame) const {
  if (frame.empty() || frame == params_.frame_id) return ReferenceFrame{};
  const engine::BodyStore& bodies = sim_.world().bodies();
  if (const auto body = bodies.findByName(frame)) return bodyFrame(bodies, *bodies.find(*body));
  const auto pose = frameToWorld(frame);
  if (!pose) return pose.status();
  ReferenceFrame out;
  out.pose.position = pose.value().translation();
  out.pose.rotation = engine::Quat(pose.value().linear()).normalized();
  return out;
}

engine::Result<SimNode::FramedBody> SimNode::framedBody(const std::string& reference_frame,
                                                        const BodyRef& ref) const {
  const auto frame = referenceFrame(reference_frame);
  if (!frame) return engine::Status::error("reference_frame: " + frame.message());
  const auto id = sim_.resolveBody(ref);
  if (!id) return id.status();
  return FramedBody{*frame, *id};
}

bool SimNode::onSpawnBody(SpawnBody::Request& req, SpawnBody::Response& res) {
  if (req.bodies.size() > params_.limits.max_bodies) {
    return answer(res, false,
                  "bodies: " + std::to_string(req.bodies.size()) +
                      " in one request, more than ~max_bodies (" +
                      std::to_string(params_.limits.max_bodies) + ")");
  }
  std::vector<engine::BodySpec> specs;
  for (std::size_t i = 0; i < req.bodies.size(); ++i) {
    const auto spec = toBodySpec(req.bodies[i]);
    if (!spec) return answer(res, false, "bodies[" + std::to_string(i) + "]." + spec.message());
    specs.push_back(*spec);
  }
  return runOnWorldThread(res, [&] {
    SpawnBody::Request resolved = req;
    for (std::size_t i = 0; i < specs.size(); ++i) {
      const auto frame = referenceFrame(req.bodies[i].frame_id);
      if (!frame) {
        answer(res, false, "bodies[" + std::to_string(i) + "]: " + frame.message());
        return;
      }
      engine::BodySpec& spec = specs[i];
      spec.pose = poseToWorld(*frame, spec.pose);
      const Twist twist = twistToWorld(*frame, spec.pose.position, fromMsg(req.bodies[i].twist));
      setSpecTwist(spec, twist);
      resolved.bodies[i].frame_id.clear();
      resolved.bodies[i].pose = toPoseMsg(spec.pose);
      resolved.bodies[i].twist = toTwistMsg(twist);
    }
    const auto ids = sim_.spawnBodies(specs);
    if (!ids) {
      answer(res, false, ids.message());
      return;
    }
    for (const auto id : *ids) res.ids.push_back(id.packed());
    recordCommand("spawn_body", resolved);
    answer(res, true,
           "spawned " + std::to_string(ids.value().size()) + " body(ies) at " +
               describeTime(sim_.world()));
  });
}

bool SimNode::onRemoveBody(RemoveBody::Request& req, RemoveBody::Response& res) {
  std::vector<BodyRef> refs;
  for (const auto id : req.ids) refs.push_back(BodyRef{id, ""});
  for (const auto& name : req.names) {
    if (name.empty()) return answer(res, false, "names: an empty name names no body");
    refs.push_back(BodyRef{0, name});
  }
  return runOnWorldThread(res, [&] {
    const auto removed = sim_.removeBodies(refs);
    if (!removed) {
      answer(res, false, removed.message());
      return;
    }
    for (const auto id : removed.value().ids) res.removed.push_back(id.packed());
    res.joints_removed = static_cast<std::uint32_t>(removed.value().joints);
    recordCommand("remove_body", req);
    answer(res, true,
           "removed " + std::to_string(removed.value().ids.size()) + " body(ies) and " +
               std::to_string(removed.value().joints) + " joint(s)");
  });
}

bool SimNode::onSetBodyState(SetBodyState::Request& req, SetBodyState::Response& res) {
  if (!req.set_pose && !req.set_twist) {
    return answer(res, false, "neither set_pose nor set_twist: nothing to set");
  }
  const BodyRef ref{req.id, req.name};
  return runOnWorldThread(res, [&] {
    const auto target = framedBody(req.reference_frame, ref);
    if (!target) {
      answer(res, false, target.message());
      return;
    }
    const ReferenceFrame& frame = target.value().frame;
    SetBodyState::Request resolved = req;
    resolved.reference_frame.clear();
    std::optional<Transform> pose;
    std::optional<Twist> twist;
    if (req.set_pose) {
      pose = poseToWorld(frame, fromMsg(req.pose));
      resolved.pose = toPoseMsg(*pose);
    }
    if (req.set_twist) {
      const engine::BodyStore& bodies = sim_.world().bodies();
      const Vec3 origin =
          pose ? pose->position : bodies.pose(*bodies.find(target.value().id)).position;
      twist = twistToWorld(frame, origin, fromMsg(req.twist));
      resolved.twist = toTwistMsg(*twist);
    }
    const Status set = sim_.setBodyState(ref, pose, twist);
    if (!set) {
      answer(res, false, set.message());
      return;
    }
    recordCommand("set_body_state", resolved);
    answer(res, true, "set the state of " + nameOf(ref) + " at " + describeTime(sim_.world()));
  });
}

bool SimNode::onGetBodyState(GetBodyState::Request& req, GetBodyState::Response& res) {
  const BodyRef ref{req.id, req.name};
  return runOnWorldThread(res, [&] {
    const auto target = framedBody(req.reference_frame, ref);
    if (!target) {
      answer(res, false, target.message());
      return;
    }
    const ReferenceFrame& frame = target.value().frame;
    const engine::World& world = sim_.world();
    const std::size_t dense = *world.bodies().find(target.value().id);
    const Transform pose = world.bodies().pose(dense);
    res.header.stamp = ros::Time::now();
    res.header.frame_id = req.reference_frame.empty() ? params_.frame_id : req.reference_frame;
    res.step = world.stepCount();
    res.time = world.time();
    res.pose = toPoseMsg(poseInFrame(frame, pose));
    res.twist = toTwistMsg(twistInFrame(frame, pose.position, bodyTwist(world.bodies(), dense)));
    res.sleeping =
        world.bodies().type(dense) != engine::BodyType::kFixed && !world.bodies().awake(dense);
    res.mass = world.bodies().mass(dense);
    answer(res, true, "the state of " + nameOf(ref) + " at " + describeTime(world));
  });
}

bool SimNode::onApplyBodyWrench(ApplyBodyWrench::Request& req, ApplyBodyWrench::Response& res) {
  const auto mode = forceMode(req.mode);
  if (!mode) {
    return answer(res, false,
                  "mode must be ONE_STEP (0), DURATION (1), UNTIL_CLEARED (2) or CLEAR (3)");
  }
  WrenchRequest request;
  request.body = BodyRef{req.id, req.name};
  request.mode = *mode;
  request.duration = req.duration;
  return runOnWorldThread(res, [&] {
    ApplyBodyWrench::Request resolved = req;
    if (request.mode != ForceMode::kClear) {
      const auto frame = referenceFrame(req.reference_frame);
      if (!frame) {
        answer(res, false, "reference_frame: " + frame.message());
        return;
      }
      const engine::Quat& r = frame.value().pose.rotation;
      request.force = r * fromMsg(req.wrench.force);
      request.torque = r * fromMsg(req.wrench.torque);
      request.point = frame.value().pose.apply(fromMsg(req.reference_point));
      resolved.reference_frame.clear();
      resolved.wrench.force = toVector3Msg(request.force);
      resolved.wrench.torque = toVector3Msg(request.torque);
      resolved.reference_point = toPointMsg(request.point);
    }
    const auto steps = sim_.applyBodyWrench(request);
    if (!steps) {
      answer(res, false, steps.message());
      return;
    }
    res.steps = *steps;
    recordCommand("apply_body_wrench", resolved);
    const std::string who = nameOf(request.body);
    answer(res, true,
           request.mode == ForceMode::kClear ? "cleared the sustained wrenches on " + who
           : request.mode == ForceMode::kUntilCleared
               ? "wrench on " + who + " until cleared"
               : "wrench on " + who + " for " + std::to_string(*steps) + " step(s)");
  });
}

bool SimNode::onApplyBodyImpulse(ApplyBodyImpulse::Request& req, ApplyBodyImpulse::Response& res) {
  const BodyRef ref{req.id, req.name};
  return runOnWorldThread(res, [&] {
    const auto frame = referenceFrame(req.reference_frame);
    if (!frame) {
      answer(res, false, "reference_frame: " + frame.message());
      return;
    }
    const engine::Quat& r = frame.value().pose.rotation;
    const Vec3 impulse = r * fromMsg(req.impulse);
    const Vec3 angular = r * fromMsg(req.angular_impulse);
    const Vec3 point = frame.value().pose.apply(fromMsg(req.reference_point));
    const auto twist = sim_.applyBodyImpulse(ref, impulse, point, angular);
    if (!twist) {
      answer(res, false, twist.message());
      return;
    }
    ApplyBodyImpulse::Request resolved = req;
    resolved.reference_frame.clear();
    resolved.impulse = toVector3Msg(impulse);
    resolved.angular_impulse = toVector3Msg(angular);
    resolved.reference_point = toPointMsg(point);
    recordCommand("apply_body_impulse", resolved);
    const engine::BodyStore& bodies = sim_.world().bodies();
    const Vec3 origin = bodies.pose(*bodies.find(*sim_.resolveBody(ref))).position;
    // Relative to the frame as it is now (the body itself, when it is the reference).
    const auto now = referenceFrame(req.reference_frame);
    res.twist = toTwistMsg(twistInFrame(*now, origin, *twist));
    answer(res, true, "applied the impulse to " + nameOf(ref));
  });
}

}  // namespace node
}  // namespace mass_aggregate_sim
