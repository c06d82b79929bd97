#include "mass_aggregate_sim/node/diagnostics.h"

#include <cstdio>
#include <tuple>

namespace mass_aggregate_sim {
namespace node {
namespace {

using diagnostic_msgs::DiagnosticStatus;
using diagnostic_updater::DiagnosticStatusWrapper;

// Step rate: OK from this fraction of ~rate, WARN from kStepRateWarn, ERROR below.
constexpr double kStepRateTolerance = 0.9;
constexpr double kStepRateWarn = 0.5;

double seconds(const StepRateWindow::Clock::duration d) {
  return std::chrono::duration<double>(d).count();
}

std::string format(const char* pattern, const double value) {
  char text[64];
  std::snprintf(text, sizeof text, pattern, value);
  return text;
}

void addTiming(const DiagnosticInputs& in, DiagnosticStatusWrapper& out) {
  out.add("target rate (Hz)", in.rate);
  out.add("measured step rate (Hz)", in.step_rate);
  out.add("steps in window", in.window_steps);
  out.add("duration of window (s)", in.window_seconds);
  out.add("minimum acceptable rate (Hz)", kStepRateTolerance * in.rate);
  out.add("time since the last step (s)", in.since_last_step);
  out.add("real-time factor", in.real_time_factor);
  out.add("step cost mean (ms)", 1e3 * in.step_cost_mean);
  out.add("step cost max (ms)", 1e3 * in.step_cost_max);
  out.add("overruns in the period", in.overruns);
  out.add("overruns since start", in.overruns_total);
  out.add("publish cost (ms)", 1e3 * in.publish_cost);
}

}  // namespace

void StepRateWindow::restart(const Clock::time_point now) {
  samples_.clear();
  restarted_ = now;
}

void StepRateWindow::add(const std::uint64_t steps, const Clock::time_point last_step,
                         const Clock::time_point now, const Clock::duration horizon) {
  // A last step from before the restart would stretch the window over the pause.
  if (steps == 0 || last_step < restarted_) return;
  if (!samples_.empty() && samples_.back().steps == steps) return;
  samples_.push_back(Sample{steps, last_step, now});
  // Keep the newest sample that is at least `horizon` old as the window's start.
  while (samples_.size() > 2 && samples_[1].at <= now - horizon) samples_.pop_front();
}

void StepRateWindow::measure(const Clock::time_point now, DiagnosticInputs& out) const {
  out.step_rate = 0.0;
  out.window_steps = 0;
  out.window_seconds = 0.0;
  out.since_last_step = seconds(now - (samples_.empty() ? restarted_ : samples_.back().last_step));
  if (samples_.size() < 2) return;
  const Sample& first = samples_.front();
  const Sample& last = samples_.back();
  out.window_steps = last.steps - first.steps;
  out.window_seconds = seconds(last.last_step - first.last_step);
  if (out.window_seconds > 0.0) out.step_rate = out.window_steps / out.window_seconds;
}

void stepRateStatus(const DiagnosticInputs& in, DiagnosticStatusWrapper& out) {
  addTiming(in, out);
  if (in.stepping_run) {
    out.summary(DiagnosticStatus::OK, "a ~step run is under way (as fast as it can)");
    return;
  }
  if (in.paused) {
    out.summary(DiagnosticStatus::OK, "paused");
    return;
  }
  if (in.since_last_step > in.stall_after) {
    out.summary(DiagnosticStatus::ERROR, "no step for " + format("%.1f", in.since_last_step) +
                                             " s (~rate " + format("%.1f", in.rate) + " Hz)");
    return;
  }
  if (in.window_steps == 0) {
    out.summary(DiagnosticStatus::OK,
                "measuring the step rate (~rate " + format("%.1f", in.rate) + " Hz)");
    return;
  }
  const double ratio = in.rate > 0.0 ? in.step_rate / in.rate : 0.0;
  const std::string text = format("%.1f", in.step_rate) + " of " + format("%.1f", in.rate) +
                           " steps per second (real-time factor " +
                           format("%.2f", in.real_time_factor) + ")";
  if (ratio >= kStepRateTolerance) {
    out.summary(DiagnosticStatus::OK, text);
  } else if (ratio >= kStepRateWarn) {
    out.summary(DiagnosticStatus::WARN, "below ~rate: " + text);
  } else {
    out.summary(DiagnosticStatus::ERROR, "far below ~rate: " + text);
  }
}

void stepCostStatus(const DiagnosticInputs& in, DiagnosticStatusWrapper& out) {
  addTiming(in, out);
  const double period = in.rate > 0.0 ? 1.0 / in.rate : 0.0;
  const double load = period > 0.0 ? in.step_cost_mean / period : 0.0;
  out.add("step cost / period", load);
  const std::string text = format("%.2f", 1e3 * in.step_cost_mean) + " ms per step of a " +
                           format("%.2f", 1e3 * period) + " ms period";
  if (load > 1.0) {
    out.summary(DiagnosticStatus::ERROR, "a step costs more than its period: " + text);
  } else if (load >= 0.8 || static_cast<double>(in.overruns) > 0.01 * in.ticks) {
    out.summary(DiagnosticStatus::WARN, text + ", " + std::to_string(in.overruns) +
                                            " overrun(s) in " + std::to_string(in.ticks) +
                                            " ticks");
  } else {
    out.summary(DiagnosticStatus::OK, text);
  }
}

void stabilityStatus(const DiagnosticInputs& in, DiagnosticStatusWrapper& out) {
  const engine::StabilityReport& s = in.stability;
  out.add("divergence events", in.divergence_events);
  out.add("last divergence", in.last_divergence);
  out.add("binding spring or drag", s.generator);
  out.add("omega*h (a drag: rate*h)", s.omega_h);
  out.add("integrator limit on it", s.limit);
  out.add("largest stable dt (s)", s.stable_dt);
  out.add("substeps used", s.substeps_used);
  out.add("substeps needed", s.substeps_needed);
  if (in.divergence_events > 0) {
    out.summary(DiagnosticStatus::ERROR, std::to_string(in.divergence_events) +
                                             " divergence(s), last: " + in.last_divergence);
  } else if (!s.stable) {
    out.summary(DiagnosticStatus::WARN, s.message);
  } else {
    out.summary(DiagnosticStatus::OK, "no divergence; every spring and drag within its limit");
  }
}

void contactsStatus(const DiagnosticInputs& in, DiagnosticStatusWrapper& out) {
  const engine::ContactStats& c = in.contacts;
  out.add("contacts", c.contacts);
  out.add("resolver iterations", c.iterations);
  out.add("velocity iterations", c.velocity_iterations);
  out.add("position iterations", c.position_iterations);
  out.add("max_iterations per phase", in.max_iterations);
  out.add("largest penetration left (m)", c.max_penetration);
  out.add("largest closing velocity left (m/s)", c.max_closing_velocity);
  out.add("dropped", c.dropped);
  out.add("continuous hits", c.ccd_hits);
  if (c.dropped > 0) {
    out.summary(DiagnosticStatus::WARN,
                std::to_string(c.dropped) + " contact(s) dropped in the last step (max_contacts)");
  } else if (c.contacts > 0 && (c.velocity_iterations >= in.max_iterations ||
                                c.position_iterations >= in.max_iterations)) {
    out.summary(DiagnosticStatus::WARN, "the resolver used every allowed pass (max_iterations " +
                                            std::to_string(in.max_iterations) +
                                            "): contacts may be left unresolved");
  } else {
    out.summary(DiagnosticStatus::OK, std::to_string(c.contacts) + " contact(s), " +
                                          std::to_string(c.iterations) + " iteration(s)");
  }
}

void capacityStatus(const DiagnosticInputs& in, DiagnosticStatusWrapper& out) {
  out.add("particles", in.particles);
  out.add("max_particles", in.max_particles);
  out.add("links and force generators", in.links);
  out.add("max_links", in.max_links);
  out.add("sustained forces", in.sustained_forces);
  out.add("max_sustained_forces", in.max_sustained_forces);
  out.add("bodies", in.bodies);
  out.add("max_bodies", in.max_bodies);
  out.add("joints", in.joints);
  out.add("max_joints", in.max_joints);
  out.add("islands", in.islands);
  out.add("sleeping bodies", in.sleeping_bodies);
  std::string full;
  for (const auto& [name, count, limit] :
       {std::tuple<const char*, std::size_t, std::size_t>{"particles", in.particles,
                                                          in.max_particles},
        {"links and force generators", in.links, in.max_links},
        {"sustained forces", in.sustained_forces, in.max_sustained_forces},
        {"bodies", in.bodies, in.max_bodies},
        {"joints", in.joints, in.max_joints}}) {
    if (limit > 0 && 10 * count >= 9 * limit) {
      if (!full.empty()) full += "; ";
      full += std::string(name) + " " + std::to_string(count) + " of " + std::to_string(limit);
    }
  }
  if (!full.empty()) {
    out.summary(DiagnosticStatus::WARN, "at 90 % of the limit or more: " + full);
  } else {
    out.summary(DiagnosticStatus::OK, std::to_string(in.particles) + " particle(s), " +
                                          std::to_string(in.links) + " link(s), " +
                                          std::to_string(in.bodies) + " body(ies) in " +
                                          std::to_string(in.islands) + " island(s), " +
                                          std::to_string(in.sleeping_bodies) + " sleeping, " +
                                          std::to_string(in.joints) + " joint(s)");
  }
}

}  // namespace node
}  // namespace mass_aggregate_sim
