// The ~step service and the ~step action: both hand a run of N steps to the world thread, which
// takes them in slices between which it applies requests and publishes.
#include <chrono>

#include "mass_aggregate_sim/node/sim_node.h"

namespace mass_aggregate_sim {
namespace node {

bool SimNode::onStep(Step::Request& req, Step::Response& res) {
  const std::uint32_t limit = params_.max_service_steps;
  if (req.steps == 0 || req.steps > limit) {
    res.success = false;
    res.message = "steps must be in [1, " + std::to_string(limit) + "] (~max_service_steps), got " +
                  std::to_string(req.steps) +
                  (req.steps > limit ? ": for longer runs use the ~step action, which reports "
                                       "progress and can be cancelled"
                                     : "");
    return true;
  }
  StepRun run;
  run.requested = req.steps;
  run.id = next_run_id_++;
  run.cancel = std::make_shared<std::atomic<bool>>(false);
  run.finished = std::make_shared<std::promise<StepOutcome>>();
  std::future<StepOutcome> finished = run.finished->get_future();
  if (!queue_.post([this, run] { startRun(run); })) {
    res.success = false;
    res.message = "the node is shutting down";
    return true;
  }
  // The world thread fulfils the promise when the run ends, is refused, or the node stops.
  StepOutcome outcome;
  try {
    while (finished.wait_for(std::chrono::milliseconds(100)) != std::future_status::ready) {
      if (!ros::ok()) run.cancel->store(true);
    }
    outcome = finished.get();
  } catch (const std::future_error&) {
    outcome.message = "the node is shutting down";
  }
  res.success = outcome.kind == StepOutcome::kSucceeded;
  res.step = outcome.step;
  res.time = outcome.time;
  res.state_hash = outcome.state_hash;
  res.message = outcome.message;
  if (res.success) {
    res.message +=
        ": step " + std::to_string(outcome.step) + ", t = " + std::to_string(outcome.time) + " s";
  }
  return true;
}

void SimNode::onStepGoal() {
  const auto goal = step_action_.acceptNewGoal();
  // The run the previous goal had (the action server has just cancelled that goal) stops at the
  // next boundary; the world thread also ends it when the new run arrives.
  if (action_cancel_) action_cancel_->store(true);
  StepResult refused;
  const std::uint32_t limit = params_.limits.max_steps_per_request;
  if (goal->steps == 0 || goal->steps > limit) {
    refused.message = "steps must be in [1, " + std::to_string(limit) +
                      "] (~max_steps_per_request), got " + std::to_string(goal->steps);
    action_outcome_ = std::future<StepOutcome>();
    step_action_.setAborted(refused, refused.message);
    return;
  }
  StepRun run;
  run.requested = goal->steps;
  run.action = true;
  run.id = next_run_id_++;
  run.cancel = std::make_shared<std::atomic<bool>>(step_action_.isPreemptRequested());
  run.finished = std::make_shared<std::promise<StepOutcome>>();
  action_run_id_ = run.id;
  action_cancel_ = run.cancel;
  action_outcome_ = run.finished->get_future();
  if (!queue_.post([this, run] { startRun(run); })) {
    action_outcome_ = std::future<StepOutcome>();
    refused.message = "the node is shutting down";
    step_action_.setAborted(refused, refused.message);
  }
}

void SimNode::onStepPreempt() {
  if (action_cancel_) action_cancel_->store(true);
}

void SimNode::onActionTimer() {
  if (!action_outcome_.valid()) return;
  if (action_outcome_.wait_for(std::chrono::seconds(0)) != std::future_status::ready) {
    RunProgress progress;
    {
      const std::lock_guard<std::mutex> lock(progress_mutex_);
      if (!progress_.fresh || progress_.run_id != action_run_id_) return;
      progress_.fresh = false;
      progress = progress_;
    }
    if (!step_action_.isActive()) return;
    StepFeedback feedback;
    feedback.steps_done = progress.steps_done;
    feedback.step = progress.step;
    feedback.time = progress.time;
    feedback.state_hash = progress.state_hash;
    step_action_.publishFeedback(feedback);
    return;
  }
  StepOutcome outcome;
  try {
    outcome = action_outcome_.get();
  } catch (const std::future_error&) {
    outcome.message = "the node is shutting down";
  }
  if (!step_action_.isActive()) return;
  StepResult result;
  result.steps_done = outcome.steps_done;
  result.step = outcome.step;
  result.time = outcome.time;
  result.state_hash = outcome.state_hash;
  result.message = outcome.message;
  switch (outcome.kind) {
    case StepOutcome::kSucceeded:
      step_action_.setSucceeded(result, outcome.message);
      break;
    case StepOutcome::kPreempted:
      step_action_.setPreempted(result, outcome.message);
      break;
    case StepOutcome::kAborted:
      step_action_.setAborted(result, outcome.message);
      break;
  }
}

}  // namespace node
}  // namespace mass_aggregate_sim
