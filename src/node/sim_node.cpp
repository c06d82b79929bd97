#include "mass_aggregate_sim/node/sim_node.h"

#include <geometry_msgs/TransformStamped.h>
#include <rosgraph_msgs/Clock.h>
#include <visualization_msgs/MarkerArray.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <thread>
#include <tuple>
#include <utility>

#include "mass_aggregate_sim/Command.h"
#include "mass_aggregate_sim/ParticleArray.h"
#include "mass_aggregate_sim/SimStats.h"
#include "mass_aggregate_sim/node/conversions.h"
#include "mass_aggregate_sim/node/input_limits.h"

namespace mass_aggregate_sim {
namespace node {
namespace {

using engine::Result;
using engine::Status;
using engine::Vec3;

std::string describeTime(const engine::World& world) {
  std::ostringstream out;
  out.precision(9);
  out << "step " << world.stepCount() << ", t = " << world.time() << " s";
  return out.str();
}

ParticleRef refOf(const std::uint64_t id, const std::string& name) { return ParticleRef{id, name}; }

std::string nameOf(const ParticleRef& ref) {
  return ref.name.empty() ? "particle " + std::to_string(ref.id) : "'" + ref.name + "'";
}

template <typename Response>
bool answer(Response& res, const bool success, const std::string& message) {
  res.success = success;
  res.message = message;
  return true;
}

}  // namespace

Result<NodeParams> readNodeParams(ros::NodeHandle& nh) {
  for (const auto& [name, type] : std::initializer_list<std::pair<const char*, ParamType>>{
           {"publish_rate", ParamType::kNumber},
           {"frame_id", ParamType::kString},
           {"paused", ParamType::kBool},
           {"publish_clock", ParamType::kBool},
           {"publish_tf", ParamType::kBool},
           {"default_radius", ParamType::kNumber},
           {"tension_scale", ParamType::kNumber},
           {"max_particles", ParamType::kInt},
           {"max_steps_per_request", ParamType::kInt},
           {"max_links", ParamType::kInt},
           {"max_sustained_forces", ParamType::kInt},
           {"rate", ParamType::kNumber},
           {"substeps", ParamType::kInt},
           {"integrator", ParamType::kString},
           {"gravity", ParamType::kVec3}}) {
    XmlRpc::XmlRpcValue value;
    if (!nh.getParam(name, value)) continue;
    const Status typed = checkParamType(name, value, type);
    if (!typed) return typed;
  }
  NodeParams p;
  nh.param("publish_rate", p.publish_rate, p.publish_rate);
  nh.param("frame_id", p.frame_id, p.frame_id);
  nh.param("paused", p.paused, p.paused);
  nh.param("publish_clock", p.publish_clock, p.publish_clock);
  nh.param("publish_tf", p.publish_tf, p.publish_tf);
  nh.param("default_radius", p.default_radius, p.default_radius);
  nh.param("tension_scale", p.tension_scale, p.tension_scale);
  int max_particles = static_cast<int>(p.limits.max_particles);
  nh.param("max_particles", max_particles, max_particles);
  int max_steps = static_cast<int>(p.limits.max_steps_per_request);
  nh.param("max_steps_per_request", max_steps, max_steps);
  int max_links = static_cast<int>(p.limits.max_links);
  nh.param("max_links", max_links, max_links);
  int max_sustained = static_cast<int>(p.limits.max_sustained_forces);
  nh.param("max_sustained_forces", max_sustained, max_sustained);
  if (!(p.publish_rate > 0.0 && p.publish_rate <= 1000.0)) {
    return Status::error("~publish_rate: must be in (0, 1000] Hz");
  }
  if (p.frame_id.empty()) return Status::error("~frame_id: must not be empty");
  if (!(p.default_radius >= 0.0 && p.default_radius <= kMaxRadius)) {
    return Status::error("~default_radius: must be in [0, " + std::to_string(kMaxRadius) + "] m");
  }
  if (!(p.tension_scale > 0.0 && std::isfinite(p.tension_scale))) {
    return Status::error("~tension_scale: must be finite and > 0");
  }
  const Status name = checkParticleName(p.frame_id, "");
  if (!name) return Status::error("~frame_id: " + name.message());
  for (const auto& [key, value, limit] :
       {std::tuple<const char*, int, int>{"max_particles", max_particles, kMaxParticlesLimit},
        {"max_steps_per_request", max_steps, kMaxStepsPerRequestLimit},
        {"max_links", max_links, kMaxLinksLimit},
        {"max_sustained_forces", max_sustained, kMaxSustainedForcesLimit}}) {
    if (value < 1 || value > limit) {
      return Status::error("~" + std::string(key) + ": must be in [1, " + std::to_string(limit) +
                           "], got " + std::to_string(value));
    }
  }
  p.limits.max_particles = static_cast<std::size_t>(max_particles);
  p.limits.max_steps_per_request = static_cast<std::uint32_t>(max_steps);
  p.limits.max_links = static_cast<std::size_t>(max_links);
  p.limits.max_sustained_forces = static_cast<std::size_t>(max_sustained);
  p.limits.world_frame = p.frame_id;
  return p;
}

Result<LoadedScene> readScene(ros::NodeHandle& nh, const NodeParams& params) {
  SceneOverrides overrides;
  overrides.max_particles = params.limits.max_particles;
  overrides.max_links = params.limits.max_links;
  overrides.world_frame = params.frame_id;
  double rate;
  if (nh.getParam("rate", rate)) overrides.rate = rate;
  int substeps;
  if (nh.getParam("substeps", substeps)) overrides.substeps = substeps;
  std::string integrator;
  if (nh.getParam("integrator", integrator) && !integrator.empty()) {
    overrides.integrator = integrator;
  }
  std::vector<double> gravity;
  if (nh.getParam("gravity", gravity)) {
    if (gravity.size() != 3 ||
        !std::all_of(gravity.begin(), gravity.end(), [](double g) { return std::isfinite(g); })) {
      return Status::error("~gravity: expected [x, y, z] of finite numbers (m/s^2)");
    }
    overrides.gravity = Vec3(gravity[0], gravity[1], gravity[2]);
  }
  XmlRpc::XmlRpcValue scene;
  nh.getParam("scene", scene);
  return loadScene(scene, overrides);
}

SimNode::SimNode(ros::NodeHandle& private_nh, const LoadedScene& scene, const NodeParams& params)
    : params_(params),
      scene_name_(scene.name),
      rate_(scene.rate),
      sim_(scene.world, params.limits),
      paused_(params.paused),
      scene_hash_(scene.world.stateHash()),
      markers_(params.frame_id, params.tension_scale),
      nh_(private_nh),
      tf_listener_(tf_buffer_) {
  particles_pub_ = nh_.advertise<ParticleArray>("particles", 1);
  markers_pub_ = nh_.advertise<visualization_msgs::MarkerArray>("markers", 1, true);
  stats_pub_ = nh_.advertise<SimStats>("stats", 1);
  commands_pub_ = nh_.advertise<Command>("commands", 100);
  if (params_.publish_clock)
    clock_pub_ = ros::NodeHandle().advertise<rosgraph_msgs::Clock>("/clock", 1);
  publishColliderFrames();
  services_.push_back(nh_.advertiseService("spawn", &SimNode::onSpawn, this));
  services_.push_back(nh_.advertiseService("remove", &SimNode::onRemove, this));
  services_.push_back(nh_.advertiseService("set_state", &SimNode::onSetState, this));
  services_.push_back(nh_.advertiseService("apply_force", &SimNode::onApplyForce, this));
  services_.push_back(nh_.advertiseService("apply_impulse", &SimNode::onApplyImpulse, this));
  services_.push_back(nh_.advertiseService("add_link", &SimNode::onAddLink, this));
  services_.push_back(nh_.advertiseService("remove_link", &SimNode::onRemoveLink, this));
  services_.push_back(nh_.advertiseService("pause", &SimNode::onPause, this));
  services_.push_back(nh_.advertiseService("step", &SimNode::onStep, this));
  services_.push_back(nh_.advertiseService("reset", &SimNode::onReset, this));
}

ros::Time SimNode::clockTime() const {
  ros::Time t;
  t.fromSec(clock_offset_ + sim_.world().time());
  return t;
}

template <typename Response>
bool SimNode::runOnWorldThread(Response& res, std::function<void()> job) {
  if (!queue_.run(std::move(job))) return answer(res, false, "the node is shutting down");
  return true;
}

Result<Eigen::Isometry3d> SimNode::frameToWorld(const std::string& frame) const {
  if (frame.empty() || frame == params_.frame_id) return Eigen::Isometry3d::Identity();
  geometry_msgs::TransformStamped t;
  try {
    t = tf_buffer_.lookupTransform(params_.frame_id, frame, ros::Time(0), ros::Duration(0.5));
  } catch (const tf2::TransformException& error) {
    return Status::error("no transform from frame '" + frame + "' to '" + params_.frame_id +
                         "': " + error.what());
  }
  const auto& q = t.transform.rotation;
  const auto& p = t.transform.translation;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = Eigen::Quaterniond(q.w, q.x, q.y, q.z).normalized().toRotationMatrix();
  pose.translation() = Vec3(p.x, p.y, p.z);
  return pose;
}

template <typename Request>
void SimNode::recordCommand(const std::string& service, const Request& request) {
  Command command;
  command.header.stamp = clockTime();
  command.header.frame_id = params_.frame_id;
  command.sequence = commands_applied_++;
  command.step = sim_.world().stepCount();
  command.service = service;
  const std::uint32_t size = ros::serialization::serializationLength(request);
  command.request.resize(size);
  ros::serialization::OStream stream(command.request.data(), size);
  ros::serialization::serialize(stream, request);
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
    return answer(res, false,
                  "type: unknown link type '" + req.type + "' (known: " + linkTypeNames() + ")");
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
  return runOnWorldThread(res, [&] {
    const bool was = paused_;
    paused_ = req.data;
    recordCommand("pause", req);
    const std::string state = paused_ ? "paused" : "running";
    answer(res, true,
           (was == paused_ ? "already " + state : state) + " at " + describeTime(sim_.world()));
  });
}

bool SimNode::onStep(Step::Request& req, Step::Response& res) {
  return runOnWorldThread(res, [&] {
    if (!paused_) {
      answer(res, false, "the simulation is running: pause it first (~pause)");
      return;
    }
    if (req.steps == 0 || req.steps > params_.limits.max_steps_per_request) {
      answer(res, false,
             "steps must be in [1, " + std::to_string(params_.limits.max_steps_per_request) +
                 "], got " + std::to_string(req.steps));
      return;
    }
    recordCommand("step", req);
    sim_.stepMany(req.steps);
    publishClock();
    res.step = sim_.world().stepCount();
    res.time = sim_.world().time();
    res.state_hash = sim_.world().stateHash();
    answer(res, true,
           "took " + std::to_string(req.steps) + " step(s): " + describeTime(sim_.world()));
  });
}

bool SimNode::onReset(std_srvs::Trigger::Request& req, std_srvs::Trigger::Response& res) {
  return runOnWorldThread(res, [&] {
    recordCommand("reset", req);
    clock_offset_ += sim_.world().time();
    sim_.reset();
    markers_.restart();
    publishClock();
    answer(res, true, "back to the scene '" + scene_name_ + "' at " + describeTime(sim_.world()));
  });
}

void SimNode::stepOnce() {
  const Clock::time_point start = Clock::now();
  sim_.step();
  const double cost = std::chrono::duration<double>(Clock::now() - start).count();
  window_step_cost_sum_ += cost;
  window_step_cost_max_ = std::max(window_step_cost_max_, cost);
  ++window_steps_;
  const auto& divergence = sim_.world().lastDivergence();
  if (divergence && divergence->step == sim_.world().stepCount()) {
    ROS_ERROR_THROTTLE(1.0, "divergence at step %lu: particle %s: %s",
                       static_cast<unsigned long>(divergence->step),
                       divergence->particle.str().c_str(), divergence->what.c_str());
  }
}

void SimNode::publishClock() {
  if (!params_.publish_clock) return;
  rosgraph_msgs::Clock clock;
  clock.clock = clockTime();
  clock_pub_.publish(clock);
}

void SimNode::publishColliderFrames() {
  const engine::Colliders& colliders = sim_.world().colliders();
  std::vector<geometry_msgs::TransformStamped> frames;
  const auto frame = [&](const engine::ColliderId id, const Vec3& origin,
                         const Eigen::Quaterniond& orientation) {
    geometry_msgs::TransformStamped t;
    t.header.stamp = ros::Time(0);
    t.header.frame_id = params_.frame_id;
    t.child_frame_id = params_.frame_id + "/collider_" + std::to_string(id);
    t.transform.translation = toVector3Msg(origin);
    t.transform.rotation.x = orientation.x();
    t.transform.rotation.y = orientation.y();
    t.transform.rotation.z = orientation.z();
    t.transform.rotation.w = orientation.w();
    frames.push_back(t);
  };
  // Planes: z along the normal; capsules: z from a to b, origin at the middle.
  for (const auto& c : colliders.planes) {
    frame(c.id, c.normal * c.offset, Eigen::Quaterniond::FromTwoVectors(Vec3::UnitZ(), c.normal));
  }
  for (const auto& c : colliders.spheres) frame(c.id, c.center, Eigen::Quaterniond::Identity());
  for (const auto& c : colliders.boxes) frame(c.id, c.center, c.orientation.normalized());
  for (const auto& c : colliders.capsules) {
    frame(c.id, 0.5 * (c.a + c.b), Eigen::Quaterniond::FromTwoVectors(Vec3::UnitZ(), c.b - c.a));
  }
  if (!frames.empty()) static_broadcaster_.sendTransform(frames);
}

void SimNode::publishTf(const ros::Time& stamp) {
  // tf2 drops a second transform with the same stamp (paused, or just after a reset).
  if (stamp <= last_tf_stamp_) return;
  last_tf_stamp_ = stamp;
  const engine::ParticleStore& particles = sim_.world().particles();
  const auto x = particles.positions();
  std::vector<geometry_msgs::TransformStamped> transforms;
  for (std::size_t i = 0; i < particles.size(); ++i) {
    if (particles.name(i).empty()) continue;
    geometry_msgs::TransformStamped t;
    t.header.stamp = stamp;
    t.header.frame_id = params_.frame_id;
    t.child_frame_id = particles.name(i);
    t.transform.translation = toVector3Msg(x.col(i));
    t.transform.rotation.w = 1.0;
    transforms.push_back(t);
  }
  if (!transforms.empty()) tf_broadcaster_.sendTransform(transforms);
}

void SimNode::publishState(const Clock::time_point now) {
  const engine::World& world = sim_.world();
  const ros::Time stamp = clockTime();

  ParticleArray particles;
  particles.header.stamp = stamp;
  particles.header.frame_id = params_.frame_id;
  fillParticleArray(world, particles);
  particles_pub_.publish(particles);

  if (markers_pub_.getNumSubscribers() > 0) markers_pub_.publish(markers_.build(world, stamp));
  if (params_.publish_tf) publishTf(stamp);

  SimStats stats;
  stats.header.stamp = stamp;
  stats.header.frame_id = params_.frame_id;
  stats.step = world.stepCount();
  stats.time = world.time();
  stats.paused = paused_;
  stats.rate = rate_;
  const double wall = std::chrono::duration<double>(now - window_start_).count();
  const double sim_advanced = clock_offset_ + world.time() - window_sim_time_;
  stats.real_time_factor = wall > 0.0 ? sim_advanced / wall : 0.0;
  stats.step_cost_mean = window_steps_ > 0 ? window_step_cost_sum_ / window_steps_ : 0.0;
  stats.step_cost_max = window_step_cost_max_;
  stats.overruns = overruns_;
  stats.particles = world.particles().size();
  stats.force_generators = world.generators().size();
  stats.sustained_forces = sim_.sustainedForceCount();
  stats.contacts = world.lastContactStats().contacts;
  stats.resolver_iterations = static_cast<std::uint64_t>(world.lastContactStats().iterations);
  stats.kinetic_energy = world.kineticEnergy();
  stats.potential_energy = world.gravitationalEnergy() + world.springEnergy();
  stats.total_energy = stats.kinetic_energy + stats.potential_energy;
  stats.momentum = toVector3Msg(world.linearMomentum());
  stats.divergence_events = world.divergenceCount();
  if (world.lastDivergence()) {
    const auto& d = *world.lastDivergence();
    stats.last_divergence =
        "step " + std::to_string(d.step) + ", particle " + d.particle.str() + ": " + d.what;
  }
  stats.commands_applied = commands_applied_;
  stats.state_hash = world.stateHash();
  stats.scene_hash = scene_hash_;
  stats_pub_.publish(stats);

  window_start_ = now;
  window_sim_time_ = clock_offset_ + world.time();
  window_step_cost_sum_ = 0.0;
  window_step_cost_max_ = 0.0;
  window_steps_ = 0;
}

void SimNode::run() {
  ros::AsyncSpinner spinner(1);
  spinner.start();
  const auto period =
      std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(1.0 / rate_));
  const auto publish_period = std::chrono::duration_cast<Clock::duration>(
      std::chrono::duration<double>(1.0 / params_.publish_rate));
  ROS_INFO("scene '%s': %zu particles, %zu force generators, %.1f Hz%s", scene_name_.c_str(),
           sim_.world().particles().size(), sim_.world().generators().size(), rate_,
           paused_ ? ", paused" : "");
  Clock::time_point next = Clock::now();
  Clock::time_point next_publish = next;
  window_start_ = next;
  while (ros::ok()) {
    // Requests first: they are applied at the boundary before the step.
    queue_.drain();
    if (!paused_) stepOnce();
    // Every tick, paused or not, so nodes on simulated time always hear the clock.
    publishClock();
    Clock::time_point now = Clock::now();
    if (now >= next_publish) {
      publishState(now);
      next_publish += publish_period;
      if (next_publish < now) next_publish = now + publish_period;
    }
    now = Clock::now();
    next += period;
    if (now > next) {
      // Late: count it and start again from now rather than stepping faster to catch up, so the
      // debt never grows; the real-time factor shows the loss.
      if (!paused_) ++overruns_;
      next = now;
    }
    std::this_thread::sleep_until(next);
  }
  queue_.stop();
  spinner.stop();
}

}  // namespace node
}  // namespace mass_aggregate_sim
