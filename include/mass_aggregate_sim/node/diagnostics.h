#pragma once

#include <diagnostic_updater/DiagnosticStatusWrapper.h>

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <string>

#include "mass_aggregate_sim/engine/collision/collision_settings.h"
#include "mass_aggregate_sim/engine/world/stability.h"

namespace mass_aggregate_sim {
namespace node {

// What /diagnostics reports, gathered by the world thread with each published frame; the step
// rate is over a StepRateWindow, the overruns over the diagnostic period (1 s of wall time).
struct DiagnosticInputs {
  double rate = 60.0;  // Hz, ~rate
  bool paused = false;
  bool stepping_run = false;       // a ~step service or action run is under way (as fast as it can)
  double step_rate = 0.0;          // real-time steps per wall second over the window
  std::uint64_t window_steps = 0;  // step intervals the rate is measured over (0: not yet)
  double window_seconds = 0.0;     // wall time they span
  double since_last_step = 0.0;    // s of wall time since the last step (or since the restart)
  double stall_after = 1.0;        // s without a step that mean the node has stalled
  double real_time_factor = 0.0;
  double step_cost_mean = 0.0;  // s
  double step_cost_max = 0.0;   // s
  std::uint64_t ticks = 0;      // real-time ticks over the period
  std::uint64_t overruns = 0;   // of those, late ones
  std::uint64_t overruns_total = 0;
  double publish_cost = 0.0;  // s, on the publishing thread
  std::uint64_t divergence_events = 0;
  std::string last_divergence;
  engine::StabilityReport stability;
  engine::ContactStats contacts;
  int max_iterations = 20;
  std::size_t particles = 0;
  std::size_t max_particles = 0;
  std::size_t links = 0;  // force generators and links together
  std::size_t max_links = 0;
  std::size_t sustained_forces = 0;
  std::size_t max_sustained_forces = 0;
  std::size_t bodies = 0;
  std::size_t max_bodies = 0;
  std::size_t joints = 0;
  std::size_t max_joints = 0;
  std::size_t islands = 0;
  std::size_t sleeping_bodies = 0;
};

// The step rate as a frequency status against ~rate, on the wall clock: fed at each diagnostic
// update with the count of real-time steps and the wall time of the last one, it measures the
// rate between the last steps of two updates, the older at least `horizon` before the newer
// (the last 5 updates, and at least 2.5 step periods at low ~rate), so the count is exact
// whatever the phase of the steps against the updates. diagnostic_updater::FrequencyStatus is not
// used: it reads ros::Time::now(), the node's own simulated /clock under /use_sim_time (always
// ~rate steps per simulated second, or a window of 0 s without /clock), and counts events per
// window, which at ~rate 1 Hz or less is 0 or 1 per update.
class StepRateWindow {
 public:
  using Clock = std::chrono::steady_clock;
  // Forgets what it measured (a pause, a ~step run, a new ~rate): measures from `now` on.
  void restart(Clock::time_point now);
  // One update: `steps` real-time steps since start, the last taken at `last_step`.
  void add(std::uint64_t steps, Clock::time_point last_step, Clock::time_point now,
           Clock::duration horizon);
  // Fills step_rate, window_steps, window_seconds and since_last_step.
  void measure(Clock::time_point now, DiagnosticInputs& out) const;

 private:
  struct Sample {
    std::uint64_t steps;
    Clock::time_point last_step;
    Clock::time_point at;
  };
  std::deque<Sample> samples_;  // only those whose last step came after the restart
  Clock::time_point restarted_;
};

// The thresholds (README, Diagnostics):
// Step rate: paused or in a ~step run: OK ("paused"); no step for stall_after: ERROR; else
// measured / ~rate >= 0.9 OK (10 % tolerance), >= 0.5 WARN, below ERROR; before two steps were
// measured since a restart, OK ("measuring").
void stepRateStatus(const DiagnosticInputs& in, diagnostic_updater::DiagnosticStatusWrapper& out);
// Step cost: mean cost / period < 0.8 and overruns <= 1 % of the ticks: OK; mean cost over the
// period: ERROR (the node cannot keep ~rate); else WARN.
void stepCostStatus(const DiagnosticInputs& in, diagnostic_updater::DiagnosticStatusWrapper& out);
// Stability: a divergence since the scene was (re)loaded: ERROR; the stiffest spring beyond the
// integrator's limit at dt / substeps: WARN; else OK.
void stabilityStatus(const DiagnosticInputs& in, diagnostic_updater::DiagnosticStatusWrapper& out);
// Contacts: contacts dropped (max_contacts) or a phase that used every allowed pass: WARN; else OK.
void contactsStatus(const DiagnosticInputs& in, diagnostic_updater::DiagnosticStatusWrapper& out);
// Capacity: a count (particles, links, sustained forces, bodies, joints) at 90 % of its limit or
// more: WARN (at 100 % such requests are refused); else OK. Also shows the islands and the
// sleeping bodies.
void capacityStatus(const DiagnosticInputs& in, diagnostic_updater::DiagnosticStatusWrapper& out);

}  // namespace node
}  // namespace mass_aggregate_sim
