#include "mass_aggregate_sim/node/sim_node.h"

#include <geometry_msgs/TransformStamped.h>
#include <rosgraph_msgs/Clock.h>
#include <visualization_msgs/MarkerArray.h>

#include <algorithm>
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

using engine::Vec3;

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

  // Building a 10,000-particle message costs time in this (the stepping) thread: only when
  // someone listens.
  if (particles_pub_.getNumSubscribers() > 0) {
    ParticleArray particles;
    particles.header.stamp = stamp;
    particles.header.frame_id = params_.frame_id;
    fillParticleArray(world, particles);
    particles_pub_.publish(particles);
  }

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
  stats.publish_cost = last_publish_cost_;
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
      last_publish_cost_ = std::chrono::duration<double>(Clock::now() - now).count();
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
