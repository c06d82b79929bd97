// SimNode's publishing thread: messages, tf and /diagnostics, from the latest frame the world
// thread handed over.
#include <geometry_msgs/TransformStamped.h>
#include <ros/topic_manager.h>

#include <algorithm>

#include "mass_aggregate_sim/node/body_conversions.h"
#include "mass_aggregate_sim/node/conversions.h"
#include "mass_aggregate_sim/node/sim_node.h"

namespace mass_aggregate_sim {
namespace node {

void SimNode::publishTf(const Frame& frame) {
  // tf2 drops a second transform with the same stamp (paused under simulated time).
  const BodySnapshot& bodies = frame.world.bodies;
  if (frame.stamp <= last_tf_stamp_ || frame.world.named + bodies.named == 0) return;
  last_tf_stamp_ = frame.stamp;
  std::vector<geometry_msgs::TransformStamped> transforms;
  transforms.reserve(frame.world.named + bodies.named);
  for (std::size_t i = 0; i < frame.world.ids.size(); ++i) {
    if (frame.world.names[i].empty()) continue;
    geometry_msgs::TransformStamped t;
    t.header.stamp = frame.stamp;
    t.header.frame_id = params_.frame_id;
    t.child_frame_id = frame.world.names[i];
    t.transform.translation = toVector3Msg(frame.world.positions.col(i));
    t.transform.rotation.w = 1.0;
    transforms.push_back(t);
  }
  // A named body's frame: its own frame (the pose ~spawn_body and ~bodies use), not its mass frame.
  for (std::size_t i = 0; i < bodies.ids.size(); ++i) {
    if (bodies.names[i].empty()) continue;
    geometry_msgs::TransformStamped t;
    t.header.stamp = frame.stamp;
    t.header.frame_id = params_.frame_id;
    t.child_frame_id = bodies.names[i];
    const engine::Transform& pose = bodies.poses[i];
    t.transform.translation = toVector3Msg(pose.position);
    t.transform.rotation.x = pose.rotation.x();
    t.transform.rotation.y = pose.rotation.y();
    t.transform.rotation.z = pose.rotation.z();
    t.transform.rotation.w = pose.rotation.w();
    transforms.push_back(t);
  }
  tf_broadcaster_.sendTransform(transforms);
}

void SimNode::publishFrame(const Frame& frame) {
  if (frame.scene_generation != markers_generation_) {
    markers_.restart();
    markers_generation_ = frame.scene_generation;
  }
  // Building a 10,000-particle message is the costly part: only when someone listens.
  if (particles_pub_.getNumSubscribers() > 0) {
    ParticleArray particles;
    particles.header.stamp = frame.stamp;
    particles.header.frame_id = params_.frame_id;
    fillParticleArray(frame.world, particles);
    particles_pub_.publish(particles);
  }
  if (markers_pub_.getNumSubscribers() > 0) {
    markers_pub_.publish(markers_.build(frame.world, colliders_, frame.stamp));
  }
  publishBodies(frame);
  if (params_.publish_tf) publishTf(frame);
  stats_pub_.publish(frame.stats);
}

void SimNode::publishBodies(const Frame& frame) {
  const BodySnapshot& bodies = frame.world.bodies;
  if (bodies_pub_.getNumSubscribers() > 0) {
    BodyArray msg;
    msg.header.stamp = frame.stamp;
    msg.header.frame_id = params_.frame_id;
    fillBodyArray(bodies, frame.world.step, frame.world.time, msg);
    bodies_pub_.publish(msg);
  }
  if (contacts_pub_.getNumSubscribers() > 0) {
    BodyContactArray msg;
    msg.header.stamp = frame.stamp;
    msg.header.frame_id = params_.frame_id;
    fillContacts(bodies, frame.world.ids, frame.world.names, frame.world.step, frame.world.time,
                 msg);
    contacts_pub_.publish(msg);
  }
  if (!bodies.hinges.empty() && joint_states_pub_.getNumSubscribers() > 0) {
    sensor_msgs::JointState msg;
    msg.header.stamp = frame.stamp;
    fillJointStates(bodies, msg);
    joint_states_pub_.publish(msg);
  }
}

void SimNode::updateDiagnostics() {
  if (!have_frame_) return;
  const Frame& frame = frames_.front();
  DiagnosticInputs& d = diagnostic_inputs_;
  d = frame.diagnostics;
  // The step rate is measured while the node steps in real time at one ~rate; a pause, a ~step
  // run or a new ~rate starts the measurement again.
  const Clock::time_point now = Clock::now();
  const bool measuring = !d.paused && !d.stepping_run;
  if (measuring != step_rate_measuring_ || d.rate != step_rate_hz_) step_rate_.restart(now);
  step_rate_measuring_ = measuring;
  step_rate_hz_ = d.rate;
  const double period = params_.diagnostic_period;
  const double horizon = std::max(5.0 * period, 2.5 / d.rate);
  step_rate_.add(
      frame.ticks_total, frame.last_tick, now,
      std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(horizon)));
  step_rate_.measure(now, d);
  d.stall_after = std::max(2.0 / d.rate, 2.0 * period);
  d.ticks = frame.ticks_total - diagnostics_ticks_;
  d.overruns = frame.stats.overruns - diagnostics_overruns_;
  diagnostics_ticks_ = frame.ticks_total;
  diagnostics_overruns_ = frame.stats.overruns;
  diagnostics_.force_update();
}

void SimNode::publishLoop() {
  const auto diagnostic_period = std::chrono::duration_cast<Clock::duration>(
      std::chrono::duration<double>(params_.diagnostic_period));
  Clock::time_point next_diagnostics = Clock::now() + diagnostic_period;
  // The startup line goes through rosconsole once rosout listens (what the node logs before
  // rosout has connected never reaches rosout.log), or after 3 s without rosout.
  const Clock::time_point startup_deadline = Clock::now() + std::chrono::seconds(3);
  bool startup_logged = false;
  while (true) {
    if (!startup_logged && (ros::TopicManager::instance()->getNumSubscribers("/rosout") > 0 ||
                            Clock::now() >= startup_deadline)) {
      ROS_INFO("%s", startup_line_.c_str());
      startup_logged = true;
    }
    const bool fresh = frames_.take(std::chrono::milliseconds(50));
    if (frames_.stopped()) break;
    if (fresh) {
      const Clock::time_point start = Clock::now();
      if (!have_frame_) {
        diagnostics_ticks_ = frames_.front().ticks_total;
        diagnostics_overruns_ = frames_.front().stats.overruns;
        have_frame_ = true;
      }
      publishFrame(frames_.front());
      last_publish_cost_ = std::chrono::duration<double>(Clock::now() - start).count();
    }
    const Clock::time_point now = Clock::now();
    if (now >= next_diagnostics && have_frame_) {
      updateDiagnostics();
      next_diagnostics += diagnostic_period;
      if (next_diagnostics < now) next_diagnostics = now + diagnostic_period;
    }
  }
}

}  // namespace node
}  // namespace mass_aggregate_sim
