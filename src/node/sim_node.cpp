// SimNode's construction and its world thread: the fixed-rate loop, ~step runs, frames.
#include "mass_aggregate_sim/node/sim_node.h"

#include <geometry_msgs/TransformStamped.h>
#include <rosgraph_msgs/Clock.h>
#include <std_msgs/String.h>

#include <algorithm>
#include <cstdio>
#include <thread>
#include <utility>

#include "mass_aggregate_sim/Command.h"
#include "mass_aggregate_sim/node/body_conversions.h"
#include "mass_aggregate_sim/node/conversions.h"
#include "mass_aggregate_sim/node/reconfigure.h"

namespace mass_aggregate_sim {
namespace node {

using engine::Vec3;

namespace {

// A ~step run yields to requests and publishing at least this often.
constexpr std::chrono::milliseconds kRunSlice(20);
// The longest the world thread sleeps before it looks at ros::ok() again.
constexpr std::chrono::milliseconds kShutdownCheck(100);

std::chrono::steady_clock::duration periodOf(const double hz) {
  return std::chrono::duration_cast<std::chrono::steady_clock::duration>(
      std::chrono::duration<double>(1.0 / hz));
}

}  // namespace

SimNode::SimNode(ros::NodeHandle& private_nh, const LoadedScene& scene, const NodeParams& params)
    : params_(params),
      scene_name_(scene.name),
      scene_source_(scene.source),
      parameters_(describeParameters(params, scene)),
      rate_(scene.rate),
      publish_rate_(params.publish_rate),
      sim_(scene.world, params.limits, scene.joint_names),
      paused_(params.paused),
      scene_hash_(sceneHash(scene.world)),
      configuration_(describeConfiguration(sim_.settings())),
      colliders_(scene.world.colliders()),
      markers_(params.frame_id, params.tension_scale, params.contact_markers),
      nh_(private_nh),
      tf_listener_(tf_buffer_),
      step_nh_(private_nh),
      step_action_(private_nh, "step", false),
      diagnostics_(ros::NodeHandle(), private_nh) {
  particles_pub_ = nh_.advertise<ParticleArray>("particles", 1);
  bodies_pub_ = nh_.advertise<BodyArray>("bodies", 1);
  contacts_pub_ = nh_.advertise<BodyContactArray>("contacts", 1);
  joint_states_pub_ = nh_.advertise<sensor_msgs::JointState>("joint_states", 1);
  markers_pub_ = nh_.advertise<visualization_msgs::MarkerArray>("markers", 1, true);
  stats_pub_ = nh_.advertise<SimStats>("stats", 1);
  commands_pub_ = nh_.advertise<Command>("commands", 100);
  configuration_pub_ = nh_.advertise<std_msgs::String>("configuration", 1, true);
  if (params_.publish_clock)
    clock_pub_ = ros::NodeHandle().advertise<rosgraph_msgs::Clock>("/clock", 1);
  publishColliderFrames();
  std_msgs::String configuration;
  configuration.data = configuration_;
  configuration_pub_.publish(configuration);

  services_.push_back(nh_.advertiseService("spawn", &SimNode::onSpawn, this));
  services_.push_back(nh_.advertiseService("remove", &SimNode::onRemove, this));
  services_.push_back(nh_.advertiseService("set_state", &SimNode::onSetState, this));
  services_.push_back(nh_.advertiseService("apply_force", &SimNode::onApplyForce, this));
  services_.push_back(nh_.advertiseService("apply_impulse", &SimNode::onApplyImpulse, this));
  services_.push_back(nh_.advertiseService("add_link", &SimNode::onAddLink, this));
  services_.push_back(nh_.advertiseService("remove_link", &SimNode::onRemoveLink, this));
  services_.push_back(nh_.advertiseService("spawn_body", &SimNode::onSpawnBody, this));
  services_.push_back(nh_.advertiseService("remove_body", &SimNode::onRemoveBody, this));
  services_.push_back(nh_.advertiseService("set_body_state", &SimNode::onSetBodyState, this));
  services_.push_back(nh_.advertiseService("get_body_state", &SimNode::onGetBodyState, this));
  services_.push_back(nh_.advertiseService("apply_body_wrench", &SimNode::onApplyBodyWrench, this));
  services_.push_back(
      nh_.advertiseService("apply_body_impulse", &SimNode::onApplyBodyImpulse, this));
  services_.push_back(nh_.advertiseService("add_joint", &SimNode::onAddJoint, this));
  services_.push_back(nh_.advertiseService("remove_joint", &SimNode::onRemoveJoint, this));
  services_.push_back(nh_.advertiseService("add_body_spring", &SimNode::onAddBodySpring, this));
  services_.push_back(nh_.advertiseService("add_force_field", &SimNode::onAddForceField, this));
  services_.push_back(
      nh_.advertiseService("remove_force_field", &SimNode::onRemoveForceField, this));
  services_.push_back(nh_.advertiseService("set_hinge_motor", &SimNode::onSetHingeMotor, this));
  services_.push_back(nh_.advertiseService("raycast", &SimNode::onRaycast, this));
  services_.push_back(nh_.advertiseService("overlap", &SimNode::onOverlap, this));
  services_.push_back(nh_.advertiseService("pause", &SimNode::onPause, this));
  services_.push_back(nh_.advertiseService("reset", &SimNode::onReset, this));
  step_nh_.setCallbackQueue(&step_queue_);
  step_service_ = step_nh_.advertiseService("step", &SimNode::onStep, this);

  step_action_.registerGoalCallback([this] { onStepGoal(); });
  step_action_.registerPreemptCallback([this] { onStepPreempt(); });
  action_timer_ = nh_.createWallTimer(ros::WallDuration(0.01),
                                      [this](const ros::WallTimerEvent&) { onActionTimer(); });

  // The reconfigure server starts from the parameter server; the node's real settings (the
  // scene's, with the parameters as overrides) replace that before the callback is set, so the
  // server and the parameter server show what runs.
  reconfigure_ = std::make_unique<dynamic_reconfigure::Server<SimConfig>>(reconfigure_mutex_, nh_);
  syncReconfigure([this](LiveSettings& shown) {
    shown = liveSettingsOf(sim_.settings(), publish_rate_, paused_);
  });
  reconfigure_->setCallback(
      [this](SimConfig& config, const std::uint32_t level) { onReconfigure(config, level); });

  diagnostics_.setHardwareID(scene_name_.empty() ? "mass_aggregate_sim" : scene_name_);
  diagnostics_.add("Step rate", [this](diagnostic_updater::DiagnosticStatusWrapper& out) {
    stepRateStatus(diagnostic_inputs_, out);
  });
  diagnostics_.add("Step cost", [this](diagnostic_updater::DiagnosticStatusWrapper& out) {
    stepCostStatus(diagnostic_inputs_, out);
  });
  diagnostics_.add("Stability", [this](diagnostic_updater::DiagnosticStatusWrapper& out) {
    stabilityStatus(diagnostic_inputs_, out);
  });
  diagnostics_.add("Contacts", [this](diagnostic_updater::DiagnosticStatusWrapper& out) {
    contactsStatus(diagnostic_inputs_, out);
  });
  diagnostics_.add("Capacity", [this](diagnostic_updater::DiagnosticStatusWrapper& out) {
    capacityStatus(diagnostic_inputs_, out);
  });
}

SimNode::~SimNode() {
  frames_.stop();
  if (publisher_.joinable()) publisher_.join();
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
  ++steps_total_;
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
  // Where each kind puts its frame (ShapeKind::describe): planes z along the normal, capsules z
  // from a to b with the origin at the middle.
  colliders_.forEach([&](const auto& shapes) {
    using Shape = typename std::decay_t<decltype(shapes)>::value_type;
    for (const Shape& shape : shapes) {
      const engine::ShapeDescription description = engine::ShapeKind<Shape>::describe(shape);
      frame(shape.id, description.origin, description.orientation);
    }
  });
  if (!frames.empty()) static_broadcaster_.sendTransform(frames);
}

void SimNode::configurationChanged() {
  configuration_ = describeConfiguration(sim_.settings());
  std_msgs::String configuration;
  configuration.data = configuration_;
  configuration_pub_.publish(configuration);
}

void SimNode::startRun(StepRun run) {
  const auto refuse = [&](const StepOutcome::Kind kind, const std::string& message) {
    StepOutcome outcome;
    outcome.kind = kind;
    outcome.step = sim_.world().stepCount();
    outcome.time = sim_.world().time();
    outcome.state_hash = sim_.world().stateHash();
    outcome.message = message;
    run.finished->set_value(outcome);
  };
  if (run_) {
    // A new action goal replaces the action's own run (the action server has cancelled it).
    if (run.action && run_->action) {
      finishRun(StepOutcome::kPreempted, "replaced by a new goal after " +
                                             std::to_string(run_->done) + " of " +
                                             std::to_string(run_->requested) + " steps");
    } else {
      refuse(StepOutcome::kAborted,
             std::string("another step run is under way (") +
                 (run_->action ? "the ~step action" : "a ~step service call") + ", " +
                 std::to_string(run_->done) + " of " + std::to_string(run_->requested) +
                 " steps done)");
      return;
    }
  }
  if (run.cancel->load()) {
    refuse(StepOutcome::kPreempted, "cancelled before it started");
    return;
  }
  if (!paused_) {
    refuse(StepOutcome::kAborted, "the simulation is running: pause it first (~pause)");
    return;
  }
  run_ = std::move(run);
}

void SimNode::finishRun(const StepOutcome::Kind kind, const std::string& message) {
  if (!run_) return;
  StepOutcome outcome;
  outcome.kind = kind;
  outcome.steps_done = run_->done;
  outcome.step = sim_.world().stepCount();
  outcome.time = sim_.world().time();
  outcome.state_hash = sim_.world().stateHash();
  outcome.message = message;
  if (run_->done > 0) {
    Step::Request taken;
    taken.steps = run_->done;
    recordCommand("step", taken);
  }
  publishClock();
  const std::shared_ptr<std::promise<StepOutcome>> finished = run_->finished;
  run_.reset();
  finished->set_value(outcome);
  frames_.wake();
}

void SimNode::runSlice(const Clock::time_point until) {
  while (run_ && run_->done < run_->requested) {
    if (run_->cancel->load()) {
      finishRun(StepOutcome::kPreempted, "cancelled after " + std::to_string(run_->done) + " of " +
                                             std::to_string(run_->requested) + " steps");
      return;
    }
    if (sim_.world().paused()) {
      finishRun(StepOutcome::kAborted,
                "the world stopped itself after a divergence (divergence_policy pause) after " +
                    std::to_string(run_->done) + " steps: ~reset to go on");
      return;
    }
    stepOnce();
    ++run_->done;
    if (Clock::now() >= until) break;
  }
  if (run_ && run_->done >= run_->requested) {
    finishRun(StepOutcome::kSucceeded, "took " + std::to_string(run_->done) + " step(s)");
  }
}

void SimNode::fillFrame(const Clock::time_point now) {
  const engine::World& world = sim_.world();
  Frame& frame = frames_.back();
  // Contacts are copied only for someone who shows them.
  const bool contacts = contacts_pub_.getNumSubscribers() > 0 ||
                        (params_.contact_markers && markers_pub_.getNumSubscribers() > 0);
  takeSnapshot(world, frame.world, sim_.jointNames(), contacts);
  frame.stamp = ros::Time::now();
  frame.taken = now;
  frame.scene_generation = scene_generation_;
  frame.steps_total = steps_total_;
  frame.ticks_total = ticks_total_;
  frame.last_tick = last_tick_;

  SimStats& stats = frame.stats;
  stats.header.stamp = frame.stamp;
  stats.header.frame_id = params_.frame_id;
  stats.step = world.stepCount();
  stats.time = world.time();
  stats.paused = paused_;
  stats.rate = rate_;
  // A window closes at the first frame with a step in it (or at every frame when nothing steps):
  // below ~publish_rate most frames fall between two steps, and a window of one of them would
  // read a real-time factor of 0 or of rate / publish_rate times too much.
  const bool close_window = window_steps_ > 0 || (paused_ && !run_);
  if (close_window) {
    const double wall = std::chrono::duration<double>(now - window_start_).count();
    const double sim_advanced = clock_offset_ + world.time() - window_sim_time_;
    window_real_time_factor_ = wall > 0.0 ? sim_advanced / wall : 0.0;
    window_step_cost_mean_ = window_steps_ > 0 ? window_step_cost_sum_ / window_steps_ : 0.0;
    window_step_cost_peak_ = window_step_cost_max_;
  }
  stats.real_time_factor = window_real_time_factor_;
  stats.step_cost_mean = window_step_cost_mean_;
  stats.step_cost_max = window_step_cost_peak_;
  stats.overruns = overruns_;
  stats.publish_cost = last_publish_cost_.load();
  stats.frame_cost = last_frame_cost_;
  stats.particles = world.particles().size();
  stats.force_generators = world.generators().size() + world.bodyGenerators().size();
  stats.sustained_forces = sim_.sustainedForceCount();
  const BodySnapshot& bodies = frame.world.bodies;
  stats.bodies = bodies.ids.size();
  stats.joints = bodies.joint_count;
  stats.islands = bodies.islands;
  stats.sleeping_bodies = bodies.sleeping_count;
  stats.body_contacts = bodies.contact_count;
  stats.contacts = world.lastContactStats().contacts;
  stats.resolver_iterations = static_cast<std::uint64_t>(world.lastContactStats().iterations);
  stats.kinetic_energy = world.kineticEnergy();
  stats.potential_energy = world.gravitationalEnergy() + world.springEnergy();
  stats.total_energy = stats.kinetic_energy + stats.potential_energy;
  stats.momentum = toVector3Msg(world.linearMomentum());
  stats.divergence_events = world.divergenceCount();
  stats.last_divergence.clear();
  if (world.lastDivergence()) {
    const auto& d = *world.lastDivergence();
    stats.last_divergence =
        "step " + std::to_string(d.step) + ", particle " + d.particle.str() + ": " + d.what;
  }
  stats.commands_applied = commands_applied_;
  // World::stateHash() costs about half a step of a large pile (it hashes every contact's warm
  // start too): while running in real time, once a second; else whenever the state changed.
  const std::pair<std::uint64_t, std::uint64_t> state{steps_total_, commands_applied_};
  const bool real_time = !paused_ && !run_;
  if (state != hashed_state_ &&
      (!real_time || now - hashed_at_ >= std::chrono::seconds(1) || window_steps_ == 0)) {
    state_hash_ = world.stateHash();
    state_hash_step_ = world.stepCount();
    hashed_state_ = state;
    hashed_at_ = now;
  }
  stats.state_hash = state_hash_;
  stats.state_hash_step = state_hash_step_;
  stats.scene_hash = scene_hash_;
  if (run_ && run_->action) {
    const std::lock_guard<std::mutex> lock(progress_mutex_);
    progress_ = RunProgress{run_->id, run_->done, stats.step, stats.time, stats.state_hash, true};
  }

  DiagnosticInputs& d = frame.diagnostics;
  d.rate = rate_;
  d.paused = paused_;
  d.stepping_run = run_.has_value();
  d.real_time_factor = stats.real_time_factor;
  d.step_cost_mean = stats.step_cost_mean;
  d.step_cost_max = stats.step_cost_max;
  d.overruns_total = overruns_;
  d.publish_cost = stats.publish_cost;
  d.divergence_events = stats.divergence_events;
  d.last_divergence = stats.last_divergence;
  d.stability = world.stabilityReport();
  d.contacts = world.lastContactStats();
  d.max_iterations = world.collisionSettings().max_iterations;
  d.particles = world.particles().size();
  d.max_particles = params_.limits.max_particles;
  d.links = world.generators().size() + world.bodyGenerators().size() + world.links().size();
  d.max_links = params_.limits.max_links;
  d.sustained_forces = sim_.sustainedForceCount();
  d.max_sustained_forces = params_.limits.max_sustained_forces;
  d.bodies = stats.bodies;
  d.max_bodies = params_.limits.max_bodies;
  d.joints = stats.joints;
  d.max_joints = params_.limits.max_joints;
  d.islands = stats.islands;
  d.sleeping_bodies = stats.sleeping_bodies;

  if (close_window) {
    window_start_ = now;
    window_sim_time_ = clock_offset_ + world.time();
    window_step_cost_sum_ = 0.0;
    window_step_cost_max_ = 0.0;
    window_steps_ = 0;
  }
  frames_.publish();
  last_frame_cost_ = std::chrono::duration<double>(Clock::now() - now).count();
}

void SimNode::run() {
  ros::AsyncSpinner spinner(1);
  spinner.start();
  step_spinner_ = std::make_unique<ros::AsyncSpinner>(1, &step_queue_);
  step_spinner_->start();
  step_action_.start();
  char startup[512];
  std::snprintf(
      startup, sizeof startup,
      "scene '%s' from %s: %zu particles, %zu force generators, %zu bodies, %zu joints, %.1f "
      "Hz%s; scene hash %lu",
      scene_name_.c_str(), scene_source_.c_str(), sim_.world().particles().size(),
      sim_.world().generators().size() + sim_.world().bodyGenerators().size(),
      sim_.world().bodies().size(), sim_.world().joints().size(), rate_, paused_ ? ", paused" : "",
      static_cast<unsigned long>(scene_hash_));
  // What an earlier launch or reconfigure left on the master is read as well (a bare rosrun
  // does not clear it): named here, so it is never silent.
  startup_line_ = std::string(startup) + "; " +
                  (parameters_.empty()
                       ? "no parameter on the parameter server changes a default"
                       : "from the parameter server, differing from the defaults: " + parameters_);
  publisher_ = std::thread([this] { publishLoop(); });
  Clock::time_point next_tick = Clock::now();
  Clock::time_point next_publish = next_tick;
  window_start_ = next_tick;
  double tick_rate = rate_;
  while (ros::ok()) {
    // Requests first: they are applied at the step boundary, as soon as they arrive.
    queue_.drain();
    if (rate_ != tick_rate) {
      // A new ~rate counts from the last tick, not after a period of the old one (up to 10 s).
      next_tick += periodOf(rate_) - periodOf(tick_rate);
      tick_rate = rate_;
    }
    const Clock::duration publish_period = periodOf(publish_rate_);
    const Clock::time_point tick = Clock::now();
    bool ticked = false;
    if (run_) {
      runSlice(tick + std::min<Clock::duration>(kRunSlice, publish_period));
      publishClock();
    } else if (tick >= next_tick) {
      if (!paused_) {
        stepOnce();
        ++ticks_total_;
        last_tick_ = Clock::now();
      }
      // Every tick, paused or not, so nodes on simulated time always hear the clock.
      publishClock();
      ticked = true;
    }
    Clock::time_point now = Clock::now();
    if (now >= next_publish) {
      fillFrame(now);
      next_publish += publish_period;
      if (next_publish < now) next_publish = now + publish_period;
    }
    now = Clock::now();
    if (run_) {
      // A run steps as fast as it can; the real-time schedule starts again when it ends.
      next_tick = now;
      continue;
    }
    if (ticked) {
      next_tick += periodOf(rate_);
      if (now > next_tick) {
        // Late: count it and start again from now rather than stepping faster to catch up, so
        // the debt never grows; the real-time factor shows the loss.
        if (!paused_) ++overruns_;
        next_tick = now;
      }
    }
    // Sleeps until the next tick or frame, or until a request arrives: a request never waits
    // for the tick (at ~rate 0.1 Hz that would be 10 s). Wakes at least every kShutdownCheck to
    // see ros::ok().
    queue_.waitUntil(std::min({next_tick, next_publish, now + kShutdownCheck}));
  }
  finishRun(StepOutcome::kAborted, "the node is shutting down");
  queue_.stop();
  step_spinner_->stop();
  spinner.stop();
  frames_.stop();
  publisher_.join();
}

}  // namespace node
}  // namespace mass_aggregate_sim
