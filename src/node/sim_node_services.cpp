// The service handlers of SimNode: each checks and transforms its request on the spinner thread,
// then runs the part that touches the world as a job on the world thread.
#include <cmath>
#include <sstream>

#include "mass_aggregate_sim/Command.h"
#include "mass_aggregate_sim/node/conversions.h"
#include "mass_aggregate_sim/node/input_limits.h"
#include "mass_aggregate_sim/node/sim_node.h"
#include "service_helpers.h"

namespace mass_aggregate_sim {
namespace node {
namespace {

using engine::Result;
using engine::Status;
using engine::Vec3;

ParticleRef refOf(const std::uint64_t id, const std::string& name) { return ParticleRef{id, name}; }

std::string nameOf(const ParticleRef& ref) {
  return ref.name.empty() ? "particle " + std::to_string(ref.id) : quoteInput(ref.name);
}

}  // namespace

Result<Eigen::Isometry3d> SimNode::frameToWorld(const std::string& frame) const {
  if (frame.empty() || frame == params_.frame_id) return Eigen::Isometry3d::Identity();
  if (frame.size() > kMaxNameLength) {
    return Status::error("frame_id: at most " + std::to_string(kMaxNameLength) +
                         " characters, got " + std::to_string(frame.size()));
  }
  // What tf holds now, at the latest time both frames share: a lookup with a timeout would wait
  // on ROS time, which stands still under /use_sim_time while paused or without /clock.
  const tf2::BufferCore& tf = tf_buffer_;
  std::string error;
  geometry_msgs::TransformStamped t;
  try {
    if (!tf.canTransform(params_.frame_id, frame, ros::Time(0), &error)) {
      throw tf2::LookupException(error);
    }
    t = tf.lookupTransform(params_.frame_id, frame, ros::Time(0));
  } catch (const tf2::TransformException& exception) {
    std::string reason = exception.what();
    if (reason.size() > 2 * kMaxQuoted) reason = reason.substr(0, 2 * kMaxQuoted) + "...";
    return Status::error("unknown frame " + quoteInput(frame) +
                         ": tf has no transform from it to '" + params_.frame_id + "' (" + reason +
                         ")");
  }
  const auto& q = t.transform.rotation;
  const auto& p = t.transform.translation;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = Eigen::Quaterniond(q.w, q.x, q.y, q.z).normalized().toRotationMatrix();
  pose.translation() = Vec3(p.x, p.y, p.z);
  return pose;
}

void SimNode::recordBytes(const std::string& service, std::vector<std::uint8_t> bytes) {
  Command command;
  command.header.stamp = ros::Time::now();
  command.header.frame_id = params_.frame_id;
  command.sequence = commands_applied_++;
  command.step = sim_.world().stepCount();
  command.time = sim_.world().time();
  command.service = service;
  command.request = std::move(bytes);
  command.state_hash = sim_.world().stateHash();
  command.scene_hash = scene_hash_;
  command.configuration = configuration_;
  commands_pub_.publish(command);
}

bool SimNode::onSpawn(Spawn::Request& req, Spawn::Response& res) {
  std::vector<engine::ParticleSpec> specs;
  Spawn::Request resolved = req;
  for (std::size_t i = 0; i < req.particles.size(); ++i) {
    const std::string where = "particles[" + std::to_string(i) + "]: ";
    auto spec = toParticleSpec(req.particles[i], params_.default_radius);
    if (!spec) return answer(res, false, where + spec.message());
    const auto pose = frameToWorld(req.particles[i].frame_id);
    if (!pose) return answer(res, false, where + pose.message());
    engine::ParticleSpec s = *spec;
    s.position = *pose * s.position;
    s.velocity = pose.value().linear() * s.velocity;
    specs.push_back(s);
    resolved.particles[i].frame_id.clear();
    resolved.particles[i].position = toPointMsg(s.position);
    resolved.particles[i].velocity = toVector3Msg(s.velocity);
  }
  return runOnWorldThread(res, [&] {
    const auto ids = sim_.spawn(specs);
    if (!ids) {
      answer(res, false, ids.message());
      return;
    }
    for (const auto id : *ids) res.ids.push_back(id.packed());
    recordCommand("spawn", resolved);
    answer(res, true,
           "spawned " + std::to_string(ids.value().size()) + " particle(s) at " +
               describeTime(sim_.world()));
  });
}

bool SimNode::onRemove(Remove::Request& req, Remove::Response& res) {
  std::vector<ParticleRef> refs;
  for (const auto id : req.ids) refs.push_back(refOf(id, ""));
  for (const auto& name : req.names) {
    if (name.empty()) return answer(res, false, "names: an empty name names no particle");
    refs.push_back(refOf(0, name));
  }
  return runOnWorldThread(res, [&] {
    const auto removed = sim_.remove(refs);
    if (!removed) {
      answer(res, false, removed.message());
      return;
    }
    for (const auto id : *removed) res.removed.push_back(id.packed());
    recordCommand("remove", req);
    answer(res, true, "removed " + std::to_string(removed.value().size()) + " particle(s)");
  });
}

bool SimNode::onSetState(SetState::Request& req, SetState::Response& res) {
  const auto pose = frameToWorld(req.frame_id);
  if (!pose) return answer(res, false, pose.message());
  std::optional<Vec3> position;
  std::optional<Vec3> velocity;
  SetState::Request resolved = req;
  resolved.frame_id.clear();
  if (req.set_position) {
    position = *pose * fromMsg(req.position);
    resolved.position = toPointMsg(*position);
  }
  if (req.set_velocity) {
    velocity = pose.value().linear() * fromMsg(req.velocity);
    resolved.velocity = toVector3Msg(*velocity);
  }
  const ParticleRef ref = refOf(req.id, req.name);
  return runOnWorldThread(res, [&] {
    const Status set = sim_.setState(ref, position, velocity);
    if (!set) {
      answer(res, false, set.message());
      return;
    }
    recordCommand("set_state", resolved);
    answer(res, true, "set the state of " + nameOf(ref));
  });
}

bool SimNode::onApplyForce(ApplyForce::Request& req, ApplyForce::Response& res) {
  ForceRequest request;
  switch (req.mode) {
    case ApplyForce::Request::ONE_STEP:
      request.mode = ForceMode::kOneStep;
      break;
    case ApplyForce::Request::DURATION:
      request.mode = ForceMode::kDuration;
      break;
    case ApplyForce::Request::UNTIL_CLEARED:
      request.mode = ForceMode::kUntilCleared;
      break;
    case ApplyForce::Request::CLEAR:
      request.mode = ForceMode::kClear;
      break;
    default:
      return answer(res, false,
                    "mode must be ONE_STEP (0), DURATION (1), UNTIL_CLEARED (2) or CLEAR (3)");
  }
  const auto pose = frameToWorld(req.frame_id);
  if (!pose) return answer(res, false, pose.message());
  request.particle = refOf(req.id, req.name);
  request.force = pose.value().linear() * fromMsg(req.force);
  request.duration = req.duration;
  ApplyForce::Request resolved = req;
  resolved.frame_id.clear();
  resolved.force = toVector3Msg(request.force);
  return runOnWorldThread(res, [&] {
    const auto steps = sim_.applyForce(request);
    if (!steps) {
      answer(res, false, steps.message());
      return;
    }
    res.steps = *steps;
    recordCommand("apply_force", resolved);
    answer(res, true,
           request.mode == ForceMode::kClear
               ? "cleared the sustained forces on " + nameOf(request.particle)
           : request.mode == ForceMode::kUntilCleared
               ? "force on " + nameOf(request.particle) + " until cleared"
               : "force on " + nameOf(request.particle) + " for " + std::to_string(*steps) +
                     " step(s)");
  });
}

bool SimNode::onApplyImpulse(ApplyImpulse::Request& req, ApplyImpulse::Response& res) {
  const auto pose = frameToWorld(req.frame_id);
  if (!pose) return answer(res, false, pose.message());
  const Vec3 impulse = pose.value().linear() * fromMsg(req.impulse);
  ApplyImpulse::Request resolved = req;
  resolved.frame_id.clear();
  resolved.impulse = toVector3Msg(impulse);
  const ParticleRef ref = refOf(req.id, req.name);
  return runOnWorldThread(res, [&] {
    const auto velocity = sim_.applyImpulse(ref, impulse);
    if (!velocity) {
      answer(res, false, velocity.message());
      return;
    }
    res.velocity = toVector3Msg(*velocity);
    recordCommand("apply_impulse", resolved);
    answer(res, true, "applied the impulse to " + nameOf(ref));
  });
}

bool SimNode::onAddLink(AddLink::Request& req, AddLink::Response& res) {
  LinkRequest request;
  const auto type = parseLinkType(req.type);
  if (!type) {
    return answer(
        res, false,
        "type: unknown link type " + quoteInput(req.type) + " (known: " + linkTypeNames() + ")");
  }
  request.type = *type;
  request.a = refOf(req.a, req.a_name);
  AddLink::Request resolved = req;
  if (req.to_anchor) {
    const auto pose = frameToWorld(req.frame_id);
    if (!pose) return answer(res, false, pose.message());
    request.anchor = *pose * fromMsg(req.anchor);
    resolved.frame_id.clear();
    resolved.anchor = toPointMsg(request.anchor);
  } else {
    request.b = refOf(req.b, req.b_name);
  }
  request.stiffness = req.stiffness;
  request.damping = req.damping;
  request.rest_length = req.rest_length;
  request.max_length = req.max_length;
  request.length = req.length;
  request.restitution = req.restitution;
  for (const double value :
       {req.stiffness, req.damping, req.rest_length, req.max_length, req.length, req.restitution}) {
    if (!std::isfinite(value)) return answer(res, false, "every number must be finite");
  }
  return runOnWorldThread(res, [&] {
    const auto id = sim_.addLink(request);
    if (!id) {
      answer(res, false, id.message());
      return;
    }
    res.link_id = *id;
    recordCommand("add_link", resolved);
    answer(res, true, "added " + req.type + " link " + std::to_string(*id));
  });
}

bool SimNode::onRemoveLink(RemoveLink::Request& req, RemoveLink::Response& res) {
  return runOnWorldThread(res, [&] {
    const Status removed = sim_.removeLink(req.link_id);
    if (!removed) {
      answer(res, false, removed.message());
      return;
    }
    recordCommand("remove_link", req);
    answer(res, true, "removed link " + std::to_string(req.link_id));
  });
}

bool SimNode::onPause(std_srvs::SetBool::Request& req, std_srvs::SetBool::Response& res) {
  runOnWorldThread(res, [&] {
    const bool was = paused_;
    paused_ = req.data;
    recordCommand("pause", req);
    const std::string state = paused_ ? "paused" : "running";
    std::string note;
    if (run_ && !paused_) {
      note = " (the ~step run under way finishes first)";
    }
    answer(
        res, true,
        (was == paused_ ? "already " + state : state) + " at " + describeTime(sim_.world()) + note);
  });
  if (res.success) syncReconfigure([&](LiveSettings& shown) { shown.paused = req.data; });
  return true;
}

bool SimNode::onReset(std_srvs::Trigger::Request& req, std_srvs::Trigger::Response& res) {
  return runOnWorldThread(res, [&] {
    finishRun(StepOutcome::kAborted, "~reset while the run was under way");
    recordCommand("reset", req);
    clock_offset_ += sim_.world().time();
    sim_.reset();
    ++scene_generation_;
    publishClock();
    answer(res, true, "back to the scene '" + scene_name_ + "' at " + describeTime(sim_.world()));
  });
}

}  // namespace node
}  // namespace mass_aggregate_sim
