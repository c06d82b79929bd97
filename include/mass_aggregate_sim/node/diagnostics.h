#pragma once

#include <diagnostic_updater/DiagnosticStatusWrapper.h>

#include <cstddef>
#include <cstdint>
#include <string>

#include "mass_aggregate_sim/engine/collision/collision_settings.h"
#include "mass_aggregate_sim/engine/world/stability.h"

namespace mass_aggregate_sim {
namespace node {

// What /diagnostics reports, gathered by the world thread with each published frame; the step
// rate and the overruns are over the diagnostic period (1 s of wall time).
struct DiagnosticInputs {
  double rate = 60.0;  // Hz, ~rate
  bool paused = false;
  bool stepping_run = false;  // a ~step service or action run is under way (as fast as it can)
  double step_rate = 0.0;     // steps per wall second over the period
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
};

// The thresholds (README, Diagnostics):
// Step rate: paused or in a ~step run: OK; else measured / ~rate >= 0.9 OK, >= 0.5 WARN, ERROR.
void stepRateStatus(const DiagnosticInputs& in, diagnostic_updater::DiagnosticStatusWrapper& out);
// Step cost: mean cost / period < 0.8 and overruns <= 1 % of the ticks: OK; mean cost over the
// period: ERROR (the node cannot keep ~rate); else WARN.
void stepCostStatus(const DiagnosticInputs& in, diagnostic_updater::DiagnosticStatusWrapper& out);
// Stability: a divergence since the scene was (re)loaded: ERROR; the stiffest spring beyond the
// integrator's limit at dt / substeps: WARN; else OK.
void stabilityStatus(const DiagnosticInputs& in, diagnostic_updater::DiagnosticStatusWrapper& out);
// Contacts: contacts dropped (max_contacts) or a phase that used every allowed pass: WARN; else OK.
void contactsStatus(const DiagnosticInputs& in, diagnostic_updater::DiagnosticStatusWrapper& out);
// Capacity: a count at 90 % of its limit or more: WARN (at 100 % such requests are refused);
// else OK.
void capacityStatus(const DiagnosticInputs& in, diagnostic_updater::DiagnosticStatusWrapper& out);

}  // namespace node
}  // namespace mass_aggregate_sim
