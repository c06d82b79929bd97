#pragma once

#include <actionlib/server/simple_action_server.h>
#include <diagnostic_updater/diagnostic_updater.h>
#include <dynamic_reconfigure/server.h>
#include <ros/callback_queue.h>
#include <ros/ros.h>
#include <std_srvs/SetBool.h>
#include <std_srvs/Trigger.h>
#include <tf2_ros/static_transform_broadcaster.h>
#include <tf2_ros/transform_broadcaster.h>
#include <tf2_ros/transform_listener.h>

#include <Eigen/Geometry>
#include <atomic>
#include <chrono>
#include <future>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "mass_aggregate_sim/AddBodySpring.h"
#include "mass_aggregate_sim/AddForceField.h"
#include "mass_aggregate_sim/AddJoint.h"
#include "mass_aggregate_sim/AddLink.h"
#include "mass_aggregate_sim/ApplyBodyImpulse.h"
#include "mass_aggregate_sim/ApplyBodyWrench.h"
#include "mass_aggregate_sim/ApplyForce.h"
#include "mass_aggregate_sim/ApplyImpulse.h"
#include "mass_aggregate_sim/GetBodyState.h"
#include "mass_aggregate_sim/Overlap.h"
#include "mass_aggregate_sim/Raycast.h"
#include "mass_aggregate_sim/Remove.h"
#include "mass_aggregate_sim/RemoveBody.h"
#include "mass_aggregate_sim/RemoveForceField.h"
#include "mass_aggregate_sim/RemoveJoint.h"
#include "mass_aggregate_sim/RemoveLink.h"
#include "mass_aggregate_sim/SetBodyState.h"
#include "mass_aggregate_sim/SetHingeMotor.h"
#include "mass_aggregate_sim/SetState.h"
#include "mass_aggregate_sim/SimConfig.h"
#include "mass_aggregate_sim/SimStats.h"
#include "mass_aggregate_sim/Spawn.h"
#include "mass_aggregate_sim/SpawnBody.h"
#include "mass_aggregate_sim/Step.h"
#include "mass_aggregate_sim/StepAction.h"
#include "mass_aggregate_sim/node/body_requests.h"
#include "mass_aggregate_sim/node/diagnostics.h"
#include "mass_aggregate_sim/node/markers.h"
#include "mass_aggregate_sim/node/node_params.h"
#include "mass_aggregate_sim/node/request_queue.h"
#include "mass_aggregate_sim/node/scene_loader.h"
#include "mass_aggregate_sim/node/settings.h"
#include "mass_aggregate_sim/node/simulation.h"
#include "mass_aggregate_sim/node/snapshot.h"

namespace mass_aggregate_sim {
namespace node {

// The ROS adapter. Threads:
// * the world thread (run()) owns the world: it steps on a fixed-rate wall schedule, hands a frame
//   (a snapshot of what is published) to the publishing thread at ~publish_rate, and sleeps in
//   between on the request queue, so a request wakes it and is applied at once, between steps. A
//   ~step run (service or action) steps as fast as it can in slices of at most 20 ms, between which
//   requests apply and frames go out.
// * the publishing thread builds and publishes the messages, the action's feedback and result,
//   and /diagnostics, from the latest frame: the step timer's overruns depend on the step alone.
// * the spinner thread runs the service, action and reconfigure callbacks: they check and
//   transform their request (tf2, never waiting on a clock), queue a job and wait for the world
//   thread to apply it (at most one step). The ~step service, which waits for its steps, has a
//   thread and callback queue of its own.
class SimNode {
 public:
  SimNode(ros::NodeHandle& private_nh, const LoadedScene& scene, const NodeParams& params);
  ~SimNode();
  // Steps until ROS shuts down.
  void run();

 private:
  using Clock = std::chrono::steady_clock;

  // The outcome of a ~step run.
  struct StepOutcome {
    enum Kind { kSucceeded, kPreempted, kAborted } kind = kAborted;
    std::uint32_t steps_done = 0;
    std::uint64_t step = 0;
    double time = 0.0;
    std::uint64_t state_hash = 0;
    std::string message;
  };
  // A run of N steps, owned by the world thread while it lasts.
  struct StepRun {
    std::uint32_t requested = 0;
    std::uint32_t done = 0;
    bool action = false;
    std::uint64_t id = 0;
    std::shared_ptr<std::atomic<bool>> cancel;
    std::shared_ptr<std::promise<StepOutcome>> finished;
  };
  // Everything the publishing thread needs of one moment.
  struct Frame {
    WorldSnapshot world;
    ros::Time stamp;
    std::uint64_t scene_generation = 0;
    SimStats stats;
    DiagnosticInputs diagnostics;
    std::uint64_t steps_total = 0;  // steps since start, across resets
    std::uint64_t ticks_total = 0;  // real-time steps since start
    Clock::time_point last_tick;    // when the last of them was taken
    Clock::time_point taken;
  };
  // An action run's progress, for its feedback.
  struct RunProgress {
    std::uint64_t run_id = 0;
    std::uint32_t steps_done = 0;
    std::uint64_t step = 0;
    double time = 0.0;
    std::uint64_t state_hash = 0;
    bool fresh = false;
  };

  bool onSpawn(Spawn::Request& req, Spawn::Response& res);
  bool onRemove(Remove::Request& req, Remove::Response& res);
  bool onSetState(SetState::Request& req, SetState::Response& res);
  bool onApplyForce(ApplyForce::Request& req, ApplyForce::Response& res);
  bool onApplyImpulse(ApplyImpulse::Request& req, ApplyImpulse::Response& res);
  bool onAddLink(AddLink::Request& req, AddLink::Response& res);
  bool onRemoveLink(RemoveLink::Request& req, RemoveLink::Response& res);
  // Bodies and joints (sim_node_bodies.cpp, sim_node_joints.cpp, sim_node_queries.cpp): frames
  // are resolved on the world thread, where bodies' poses are current.
  bool onSpawnBody(SpawnBody::Request& req, SpawnBody::Response& res);
  bool onRemoveBody(RemoveBody::Request& req, RemoveBody::Response& res);
  bool onSetBodyState(SetBodyState::Request& req, SetBodyState::Response& res);
  bool onGetBodyState(GetBodyState::Request& req, GetBodyState::Response& res);
  bool onApplyBodyWrench(ApplyBodyWrench::Request& req, ApplyBodyWrench::Response& res);
  bool onApplyBodyImpulse(ApplyBodyImpulse::Request& req, ApplyBodyImpulse::Response& res);
  bool onAddJoint(AddJoint::Request& req, AddJoint::Response& res);
  bool onAddBodySpring(AddBodySpring::Request& req, AddBodySpring::Response& res);
  bool onAddForceField(AddForceField::Request& req, AddForceField::Response& res);
  bool onRemoveForceField(RemoveForceField::Request& req, RemoveForceField::Response& res);
  bool onRemoveJoint(RemoveJoint::Request& req, RemoveJoint::Response& res);
  bool onSetHingeMotor(SetHingeMotor::Request& req, SetHingeMotor::Response& res);
  bool onRaycast(Raycast::Request& req, Raycast::Response& res);
  bool onOverlap(Overlap::Request& req, Overlap::Response& res);
  bool onPause(std_srvs::SetBool::Request& req, std_srvs::SetBool::Response& res);
  bool onStep(Step::Request& req, Step::Response& res);
  bool onReset(std_srvs::Trigger::Request& req, std_srvs::Trigger::Response& res);
  // The action's callbacks and its timer all run on the spinner thread, the only one that talks
  // to the action server.
  void onStepGoal();
  void onStepPreempt();
  void onActionTimer();
  // Applies `change` to what the reconfigure server shows and publishes it (a ~pause changed
  // `paused`); never from the world thread.
  void syncReconfigure(const std::function<void(LiveSettings&)>& change);
  void onReconfigure(SimConfig& config, std::uint32_t level);

  // Queues the job for the world thread and waits; false (with the message set) when the node
  // is shutting down.
  template <typename Response>
  bool runOnWorldThread(Response& res, std::function<void()> job);
  // The transform from `frame` to ~frame_id (identity for an empty frame or ~frame_id itself),
  // from what tf has now: never waits, so an unknown frame is refused at once whatever the clock.
  engine::Result<Eigen::Isometry3d> frameToWorld(const std::string& frame) const;
  // World thread: a body's name is that body's frame as it is and moves now; any other name goes
  // to frameToWorld (taken as still); empty or ~frame_id is the world.
  engine::Result<ReferenceFrame> referenceFrame(const std::string& frame) const;
  // World thread: a body request's reference_frame and the body it names, both resolved (the
  // refusal names the field that failed).
  struct FramedBody {
    ReferenceFrame frame;
    engine::BodyId id;
  };
  engine::Result<FramedBody> framedBody(const std::string& reference_frame,
                                        const BodyRef& ref) const;
  // Publishes an accepted request on ~commands, stamped with the step it was applied at, the
  // state hash and the configuration at that boundary (before the request).
  template <typename Request>
  void recordCommand(const std::string& service, const Request& request);
  void recordBytes(const std::string& service, std::vector<std::uint8_t> bytes);

  // World thread.
  void stepOnce();
  // Starts a run (false and the outcome set when refused).
  void startRun(StepRun run);
  // Steps the run until it is done, cancelled, or `until` has passed.
  void runSlice(Clock::time_point until);
  void finishRun(StepOutcome::Kind kind, const std::string& message);
  void publishClock();
  void fillFrame(Clock::time_point now);
  void configurationChanged();
  ros::Time clockTime() const;

  // Publishing thread.
  void publishLoop();
  void publishFrame(const Frame& frame);
  void publishTf(const Frame& frame);
  // ~bodies, ~contacts and ~joint_states.
  void publishBodies(const Frame& frame);
  void updateDiagnostics();
  // One static frame per collider, <frame_id>/collider_<id>, published once.
  void publishColliderFrames();

  NodeParams params_;
  std::string scene_name_;
  std::string scene_source_;
  std::string parameters_;    // describeParameters(): what the parameter server changed
  std::string startup_line_;  // logged by the publishing thread once rosout listens
  double rate_;
  double publish_rate_;
  Simulation sim_;
  bool paused_;
  std::uint64_t scene_hash_;
  std::string configuration_;
  std::uint64_t scene_generation_ = 0;
  RequestQueue queue_;
  const engine::Colliders colliders_;
  MarkerBuilder markers_;  // publishing thread
  std::uint64_t markers_generation_ = 0;

  ros::NodeHandle nh_;
  ros::Publisher particles_pub_;
  ros::Publisher bodies_pub_;
  ros::Publisher contacts_pub_;
  ros::Publisher joint_states_pub_;
  ros::Publisher markers_pub_;
  ros::Publisher stats_pub_;
  ros::Publisher commands_pub_;
  ros::Publisher configuration_pub_;
  ros::Publisher clock_pub_;
  std::vector<ros::ServiceServer> services_;
  tf2_ros::Buffer tf_buffer_;
  tf2_ros::TransformListener tf_listener_;
  tf2_ros::TransformBroadcaster tf_broadcaster_;
  tf2_ros::StaticTransformBroadcaster static_broadcaster_;

  // The ~step service waits for its steps: on a queue and thread of its own.
  ros::CallbackQueue step_queue_;
  ros::NodeHandle step_nh_;
  ros::ServiceServer step_service_;
  std::unique_ptr<ros::AsyncSpinner> step_spinner_;

  actionlib::SimpleActionServer<StepAction> step_action_;
  ros::WallTimer action_timer_;
  std::uint64_t action_run_id_ = 0;  // the current goal's run (spinner thread)
  std::shared_ptr<std::atomic<bool>> action_cancel_;
  std::future<StepOutcome> action_outcome_;
  std::atomic<std::uint64_t> next_run_id_{1};
  std::mutex progress_mutex_;
  RunProgress progress_;  // written by the world thread, read by the action timer

  boost::recursive_mutex reconfigure_mutex_;
  std::unique_ptr<dynamic_reconfigure::Server<SimConfig>> reconfigure_;
  LiveSettings reconfigured_;  // what the reconfigure server shows (under reconfigure_mutex_)

  diagnostic_updater::Updater diagnostics_;
  Clock::time_point next_diagnostics_;
  DiagnosticInputs diagnostic_inputs_;  // what the status functions read (publishing thread)
  bool have_frame_ = false;
  std::uint64_t diagnostics_ticks_ = 0;     // ticks_total and overruns of the frame seen at the
  std::uint64_t diagnostics_overruns_ = 0;  // previous diagnostic update
  StepRateWindow step_rate_;
  bool step_rate_measuring_ = false;  // running in real time at step_rate_hz_ at the last update
  double step_rate_hz_ = 0.0;

  FrameExchange<Frame> frames_;
  std::thread publisher_;
  std::atomic<double> last_publish_cost_{0.0};
  double last_frame_cost_ = 0.0;  // world thread
  // The last state hash taken, its step, and the (steps, commands) it was taken after.
  std::uint64_t state_hash_ = 0;
  std::uint64_t state_hash_step_ = 0;
  std::pair<std::uint64_t, std::uint64_t> hashed_state_{~std::uint64_t{0}, 0};
  Clock::time_point hashed_at_;

  // World thread.
  std::optional<StepRun> run_;
  // /clock = clock_offset_ + world time: a reset adds the time reached so far to the offset, so
  // the clock never goes back.
  double clock_offset_ = 0.0;
  ros::Time last_tf_stamp_;  // publishing thread
  std::uint64_t commands_applied_ = 0;
  std::uint64_t overruns_ = 0;
  std::uint64_t steps_total_ = 0;
  std::uint64_t ticks_total_ = 0;
  Clock::time_point last_tick_;
  // Per publish window, for the real-time factor and the step cost.
  Clock::time_point window_start_;
  double window_sim_time_ = 0.0;
  double window_step_cost_sum_ = 0.0;
  double window_step_cost_max_ = 0.0;
  std::uint64_t window_steps_ = 0;
  // What the last closed window measured, published until the next one closes.
  double window_real_time_factor_ = 0.0;
  double window_step_cost_mean_ = 0.0;
  double window_step_cost_peak_ = 0.0;
};

template <typename Response>
bool SimNode::runOnWorldThread(Response& res, std::function<void()> job) {
  if (!queue_.run(std::move(job))) {
    res.success = false;
    res.message = "the node is shutting down";
  }
  return true;
}

template <typename Request>
void SimNode::recordCommand(const std::string& service, const Request& request) {
  const std::uint32_t size = ros::serialization::serializationLength(request);
  std::vector<std::uint8_t> bytes(size);
  ros::serialization::OStream stream(bytes.data(), size);
  ros::serialization::serialize(stream, request);
  recordBytes(service, std::move(bytes));
}

}  // namespace node
}  // namespace mass_aggregate_sim
