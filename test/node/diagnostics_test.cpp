#include "mass_aggregate_sim/node/diagnostics.h"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace node
}  // namespace mass_aggregate_sim
