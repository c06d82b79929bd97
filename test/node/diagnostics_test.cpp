#include "mass_aggregate_sim/node/diagnostics.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>

namespace mass_aggregate_sim {
namespace node {
namespace {

using diagnostic_msgs::DiagnosticStatus;
using diagnostic_updater::DiagnosticStatusWrapper;

template <typename Status>
DiagnosticStatusWrapper run(Status status, const DiagnosticInputs& in) {
  DiagnosticStatusWrapper out;
  status(in, out);
  return out;
}

DiagnosticInputs running(const double step_rate) {
  DiagnosticInputs in;
  in.rate = 100.0;
  in.step_rate = step_rate;
  in.window_steps = 500;
  in.window_seconds = 500 / step_rate;
  in.since_last_step = 0.01;
  in.stall_after = 2.0;
  in.ticks = 100;
  in.step_cost_mean = 0.001;
  return in;
}

TEST(DiagnosticsTest, StepRateAgainstTheTarget) {
  EXPECT_EQ(run(stepRateStatus, running(95.0)).level, DiagnosticStatus::OK);
  EXPECT_EQ(run(stepRateStatus, running(70.0)).level, DiagnosticStatus::WARN);
  EXPECT_EQ(run(stepRateStatus, running(40.0)).level, DiagnosticStatus::ERROR);
  DiagnosticInputs paused = running(0.0);
  paused.paused = true;
  EXPECT_EQ(run(stepRateStatus, paused).level, DiagnosticStatus::OK);
  EXPECT_EQ(run(stepRateStatus, paused).message, "paused");
  paused.stepping_run = true;
  paused.step_rate = 5000.0;
  EXPECT_EQ(run(stepRateStatus, paused).level, DiagnosticStatus::OK);
}

TEST(DiagnosticsTest, StepRateStallIsAnErrorMeasuringIsNot) {
  DiagnosticInputs in = running(100.0);
  in.since_last_step = 2.5;
  const auto stalled = run(stepRateStatus, in);
  EXPECT_EQ(stalled.level, DiagnosticStatus::ERROR);
  EXPECT_EQ(stalled.message, "no step for 2.5 s (~rate 100.0 Hz)");
  in.paused = true;  // a paused node takes no step: that is no stall
  EXPECT_EQ(run(stepRateStatus, in).level, DiagnosticStatus::OK);
  EXPECT_EQ(run(stepRateStatus, in).message, "paused");
  in = running(0.0);
  in.window_steps = 0;  // just resumed: fewer than two steps seen
  const auto measuring = run(stepRateStatus, in);
  EXPECT_EQ(measuring.level, DiagnosticStatus::OK);
  EXPECT_NE(measuring.message.find("measuring"), std::string::npos);
}

// Steps at 1 Hz, diagnostic updates every 0.5 s (~diagnostic_period shorter than a step): a count
// of the steps in each update's period reads 0 or 2 Hz in turn (ERROR, OK); the window measures
// between steps and reads 1 Hz at every update.
TEST(DiagnosticsTest, StepRateWindowIsExactBelowTheUpdateRate) {
  using Clock = StepRateWindow::Clock;
  const Clock::time_point t0 = Clock::now();
  const auto at = [&](const double s) {
    return t0 + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(s));
  };
  StepRateWindow window;
  window.restart(t0);
  const auto horizon = std::chrono::duration_cast<Clock::duration>(
      std::chrono::duration<double>(std::max(5 * 0.5, 2.5 / 1.0)));
  std::uint64_t steps = 0;
  double last_step = 0.0;
  for (int update = 1; update <= 40; ++update) {
    const double now = 0.5 * update;
    // Steps at 0.3 s, 1.3 s, 2.3 s, ... (a little late now and then).
    while (0.3 + steps + 0.01 * (steps % 3) <= now) {
      last_step = 0.3 + steps + 0.01 * (steps % 3);
      ++steps;
    }
    window.add(steps, at(last_step), at(now), horizon);
    DiagnosticInputs in;
    in.rate = 1.0;
    in.stall_after = 2.0;
    window.measure(at(now), in);
    if (now < 2.5) continue;  // two steps seen: from then on, a verdict
    EXPECT_GE(in.window_steps, 2u) << now;
    EXPECT_NEAR(in.step_rate, 1.0, 0.02) << now;
    EXPECT_LE(in.since_last_step, 1.0) << now;
    EXPECT_EQ(run(stepRateStatus, in).level, DiagnosticStatus::OK) << now;
  }
  // No step for 3 s: a stall, whatever the rate measured before.
  window.add(steps, at(last_step), at(20.0 + 3.0), horizon);
  DiagnosticInputs in;
  in.rate = 1.0;
  in.stall_after = 2.0;
  window.measure(at(20.0 + 3.0), in);
  EXPECT_EQ(run(stepRateStatus, in).level, DiagnosticStatus::ERROR);
  // After a pause the window starts again: what came before the restart is not counted.
  window.restart(at(30.0));
  window.add(steps + 1, at(30.5), at(31.0), horizon);
  window.measure(at(31.0), in);
  EXPECT_EQ(in.window_steps, 0u);
}

TEST(DiagnosticsTest, StepCostAgainstThePeriod) {
  DiagnosticInputs in = running(100.0);
  EXPECT_EQ(run(stepCostStatus, in).level, DiagnosticStatus::OK);
  in.step_cost_mean = 0.0085;  // of a 10 ms period
  EXPECT_EQ(run(stepCostStatus, in).level, DiagnosticStatus::WARN);
  in.step_cost_mean = 0.012;
  EXPECT_EQ(run(stepCostStatus, in).level, DiagnosticStatus::ERROR);
  in.step_cost_mean = 0.001;
  in.overruns = 2;  // of 100 ticks
  EXPECT_EQ(run(stepCostStatus, in).level, DiagnosticStatus::WARN);
}

TEST(DiagnosticsTest, DivergenceIsAnErrorAnUnstableSpringAWarning) {
  DiagnosticInputs in;
  EXPECT_EQ(run(stabilityStatus, in).level, DiagnosticStatus::OK);
  in.stability.stable = false;
  in.stability.message = "spring 3: omega*h 16.7 over the limit 2";
  const auto unstable = run(stabilityStatus, in);
  EXPECT_EQ(unstable.level, DiagnosticStatus::WARN);
  EXPECT_EQ(unstable.message, in.stability.message);
  in.divergence_events = 1;
  in.last_divergence = "step 12, particle 1: position not finite";
  const auto diverged = run(stabilityStatus, in);
  EXPECT_EQ(diverged.level, DiagnosticStatus::ERROR);
  EXPECT_NE(diverged.message.find("step 12"), std::string::npos);
}

TEST(DiagnosticsTest, ContactsWarnWhenDroppedOrOutOfPasses) {
  DiagnosticInputs in;
  in.max_iterations = 10;
  in.contacts.contacts = 50;
  in.contacts.velocity_iterations = 3;
  in.contacts.position_iterations = 2;
  EXPECT_EQ(run(contactsStatus, in).level, DiagnosticStatus::OK);
  in.contacts.velocity_iterations = 10;
  EXPECT_EQ(run(contactsStatus, in).level, DiagnosticStatus::WARN);
  in.contacts.velocity_iterations = 3;
  in.contacts.dropped = 4;
  EXPECT_EQ(run(contactsStatus, in).level, DiagnosticStatus::WARN);
}

TEST(DiagnosticsTest, CapacityWarnsFromNinetyPercent) {
  DiagnosticInputs in;
  in.max_particles = 1000;
  in.max_links = 1000;
  in.max_sustained_forces = 10;
  in.particles = 899;
  EXPECT_EQ(run(capacityStatus, in).level, DiagnosticStatus::OK);
  in.particles = 900;
  EXPECT_EQ(run(capacityStatus, in).level, DiagnosticStatus::WARN);
  in.particles = 0;
  in.sustained_forces = 10;
  const auto full = run(capacityStatus, in);
  EXPECT_EQ(full.level, DiagnosticStatus::WARN);
  EXPECT_NE(full.message.find("sustained forces 10 of 10"), std::string::npos);
}

TEST(DiagnosticsTest, CapacityCountsBodiesJointsIslandsAndSleepers) {
  DiagnosticInputs in;
  in.max_particles = in.max_links = in.max_sustained_forces = 1000;
  in.max_bodies = 100;
  in.max_joints = 10;
  in.bodies = 89;
  in.joints = 8;
  in.islands = 3;
  in.sleeping_bodies = 40;
  const auto ok = run(capacityStatus, in);
  EXPECT_EQ(ok.level, DiagnosticStatus::OK);
  EXPECT_NE(ok.message.find("89 body(ies) in 3 island(s), 40 sleeping, 8 joint(s)"),
            std::string::npos)
      << ok.message;
  in.bodies = 90;
  const auto bodies = run(capacityStatus, in);
  EXPECT_EQ(bodies.level, DiagnosticStatus::WARN);
  EXPECT_NE(bodies.message.find("bodies 90 of 100"), std::string::npos) << bodies.message;
  in.bodies = 0;
  in.joints = 9;
  const auto joints = run(capacityStatus, in);
  EXPECT_EQ(joints.level, DiagnosticStatus::WARN);
  EXPECT_NE(joints.message.find("joints 9 of 10"), std::string::npos) << joints.message;
}

}  // namespace
}  // namespace node
}  // namespace mass_aggregate_sim
