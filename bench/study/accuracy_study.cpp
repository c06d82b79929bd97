// The accuracy study of issue 5: writes CSV files into the folder named on the command line
// (scripts/accuracy_study.sh turns them into PNG plots):
//   work_precision.csv   error against CPU time per simulated second, per problem, integrator, dt
//   stability_map.csv    largest stable omega*dt per integrator (bisection) next to theory
//   energy_drift.csv     relative energy error over 1e5 steps per integrator (sampled)
//   energy_drift_summary.csv, recommendations.csv and recommendations.md (the table for users)
// and, for rigid bodies (issue 14, body_study.h), body_work_precision.csv and
// body_recommendations.csv / .md.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "body_study.h"
#include "mass_aggregate_sim/engine/world/stability.h"
#include "reference_problems.h"
#include "study_io.h"

namespace mass_aggregate_sim {
namespace study {
namespace {

using engine::integratorName;
using engine::ParticleSpec;
using engine::Spring;
using engine::WorldConfig;

const Integrator kIntegrators[] = {Integrator::kExplicitEuler,
                                   Integrator::kSemiImplicitEuler,
                                   Integrator::kPositionVerlet,
                                   Integrator::kVelocityVerlet,
                                   Integrator::kRk4,
                                   Integrator::kImplicitEuler};
const Real kTimeSteps[] = {0.2, 0.1, 0.05, 0.02, 0.01, 0.005, 0.002, 0.001, 0.0005, 0.0002};
// Errors above this (or not finite) count as diverged.
constexpr Real kDiverged = 1e3;

// The largest distance of any particle from the reference at any sample time.
Real maxPositionError(const Trajectory& run, const Trajectory& reference) {
  Real worst = 0.0;
  for (std::size_t k = 0; k < run.size(); ++k) {
    for (Eigen::Index i = 0; i < run[k].cols(); ++i) {
      const Real e = (run[k].col(i) - reference[k].col(i)).norm();
      if (!std::isfinite(e)) return std::numeric_limits<Real>::infinity();
      worst = std::max(worst, e);
    }
  }
  return worst;
}

struct Sample {
  std::string problem;
  Integrator integrator;
  Real dt;
  Real error;
  Real cpu_per_simulated_second;
  bool diverged;
};

// Work-precision: for every problem, integrator and dt, the position error over the trajectory and
// the CPU time per simulated second (runs repeated until 20 ms of CPU time are measured).
std::vector<Sample> workPrecision(const std::string& dir) {
  const ReferenceProblem problems[] = {
      undampedOscillator(), dampedOscillator(), springChain(), dragProjectile(),
      dampedProjectile(),   rodPendulum(),      rodRope()};
  FILE* csv = openCsv(dir, "work_precision.csv",
                      "problem,integrator,dt,error,cpu_s_per_simulated_s,diverged");
  std::vector<Sample> samples;
  for (const ReferenceProblem& problem : problems) {
    const Trajectory reference = referenceTrajectory(problem);
    std::fprintf(stderr, "work-precision: %s\n", problem.name.c_str());
    for (const Integrator integrator : kIntegrators) {
      for (const Real dt : kTimeSteps) {
        Trajectory result;
        int runs = 0;
        const double start = cpuSeconds();
        double elapsed = 0.0;
        do {
          result = trajectory(problem, integrator, dt);
          ++runs;
          elapsed = cpuSeconds() - start;
        } while (elapsed < kMinimumCpuSeconds);
        const Real error = maxPositionError(result, reference);
        const bool diverged = !(error < kDiverged);
        const Real cost = elapsed / runs / problem.duration;
        samples.push_back({problem.name, integrator, dt, error, cost, diverged});
        std::fprintf(csv, "%s,%s,%g,%.6e,%.6e,%d\n", problem.name.c_str(),
                     integratorName(integrator), dt, diverged ? kDiverged : error, cost,
                     diverged ? 1 : 0);
      }
    }
  }
  std::fclose(csv);
  return samples;
}

// Undamped oscillator (m = 1, anchored spring, x0 = 1) at omega h = omega_h, dt = 0.01: bounded
// when |x| stays below 1e3 over `steps` steps. A symplectic method's orbit reaches
// 1 / sqrt(1 - (omega h / 2)^2), so 1e3 puts the measured edge within 1e-6 of the true one.
bool staysBounded(const Integrator integrator, const Real omega_h, const long steps) {
  const Real dt = 0.01;
  WorldConfig config;
  config.dt = dt;
  config.integrator = integrator;
  config.energy_growth_limit = 0.0;  // measure the integrator, not the guard
  World world(config);
  ParticleSpec spec;
  spec.position = Vec3::UnitX();
  world.addParticle(spec);
  Spring spring;
  spring.a = world.particles().idAt(0);
  spring.stiffness = std::pow(omega_h / dt, 2);
  world.addGenerator(spring);
  for (long s = 0; s < steps; ++s) {
    world.step();
    const Real x = std::abs(world.particles().positions()(0, 0));
    if (!(x < 1e3)) return false;
  }
  return true;
}

void stabilityMap(const std::string& dir) {
  FILE* csv =
      openCsv(dir, "stability_map.csv", "integrator,steps,measured_omega_dt,theory_omega_dt,note");
  const long lengths[] = {1000, 10000, 100000};
  for (const Integrator integrator : kIntegrators) {
    const Real theory = engine::stabilityLimit(integrator);
    for (const long steps : lengths) {
      std::fprintf(stderr, "stability map: %s, %ld steps\n", integratorName(integrator), steps);
      // Implicit Euler is checked at large omega*h instead of bisected.
      if (std::isinf(theory)) {
        const bool bounded = staysBounded(integrator, 1e3, steps) &&
                             staysBounded(integrator, 1e6, std::min(steps, 10000L));
        std::fprintf(csv, "%s,%ld,%s,inf,%s\n", integratorName(integrator), steps,
                     bounded ? "1e6" : "0",
                     bounded ? "bounded at omega*dt = 1e3 and 1e6 (unbounded region)"
                             : "unbounded at large omega*dt");
        continue;
      }
      Real low = 0.0;
      Real high = 10.0;
      for (int i = 0; i < 40; ++i) {
        const Real mid = 0.5 * (low + high);
        (staysBounded(integrator, mid, steps) ? low : high) = mid;
      }
      const char* note = theory == 0.0 ? "grows for any omega*dt; the edge shrinks as the run "
                                         "lengthens (1e3 growth after the run)"
                                       : "";
      std::fprintf(csv, "%s,%ld,%.6f,%.6f,%s\n", integratorName(integrator), steps, low, theory,
                   note);
    }
  }
  std::fclose(csv);
}

// Undamped oscillator, omega = 1, dt = 0.05 (omega h = 0.05), 1e5 steps: |E/E0 - 1|.
void energyDrift(const std::string& dir) {
  FILE* trace = openCsv(dir, "energy_drift.csv", "integrator,step,time,relative_energy_error");
  FILE* summary = openCsv(dir, "energy_drift_summary.csv",
                          "integrator,dt,steps,final_relative_error,max_relative_error");
  const ReferenceProblem problem = undampedOscillator();
  const Real dt = 0.05;
  const long steps = 100000;
  for (const Integrator integrator : kIntegrators) {
    std::fprintf(stderr, "energy drift: %s\n", integratorName(integrator));
    World world = problem.build(integrator, dt);
    const Real initial = world.totalEnergy();
    Real worst = 0.0;
    Real relative = 0.0;
    for (long s = 1; s <= steps; ++s) {
      world.step();
      relative = std::abs(world.totalEnergy() / initial - 1.0);
      worst = std::max(worst, relative);
      if (s % 100 == 0) {
        std::fprintf(trace, "%s,%ld,%g,%.6e\n", integratorName(integrator), s, world.time(),
                     relative);
      }
    }
    std::fprintf(summary, "%s,%g,%ld,%.6e,%.6e\n", integratorName(integrator), dt, steps, relative,
                 worst);
  }
  std::fclose(trace);
  std::fclose(summary);
}

// For each problem and error tolerance, the integrator and dt that reach it at the least CPU
// time: among the dt that reach it, each integrator's cheapest, then the cheapest of those.
void recommendations(const std::string& dir, const std::vector<Sample>& samples) {
  FILE* csv = openCsv(dir, "recommendations.csv",
                      "problem,tolerance,rank,integrator,dt,error,cpu_s_per_simulated_s");
  FILE* md = std::fopen((dir + "/recommendations.md").c_str(), "w");
  std::fprintf(md,
               "| problem | error at most | best: integrator, dt (CPU per simulated s) | "
               "runner-up |\n|---|---|---|---|\n");
  const Real tolerances[] = {1e-1, 1e-2, 1e-3, 1e-4, 1e-6};
  std::vector<std::string> problems;
  for (const Sample& s : samples) {
    if (std::find(problems.begin(), problems.end(), s.problem) == problems.end()) {
      problems.push_back(s.problem);
    }
  }
  for (const std::string& problem : problems) {
    for (const Real tolerance : tolerances) {
      std::map<Integrator, const Sample*> best;
      for (const Sample& s : samples) {
        if (s.problem != problem || s.diverged || s.error > tolerance) continue;
        const Sample*& current = best[s.integrator];
        if (!current || s.cpu_per_simulated_second < current->cpu_per_simulated_second) {
          current = &s;
        }
      }
      std::vector<const Sample*> ranked;
      for (const auto& entry : best) ranked.push_back(entry.second);
      std::sort(ranked.begin(), ranked.end(), [](const Sample* a, const Sample* b) {
        return a->cpu_per_simulated_second < b->cpu_per_simulated_second;
      });
      std::string cells[2] = {"none in the sweep", "-"};
      for (std::size_t r = 0; r < ranked.size(); ++r) {
        const Sample& s = *ranked[r];
        std::fprintf(csv, "%s,%g,%zu,%s,%g,%.3e,%.3e\n", problem.c_str(), tolerance, r + 1,
                     integratorName(s.integrator), s.dt, s.error, s.cpu_per_simulated_second);
        if (r < 2) {
          char text[160];
          std::snprintf(text, sizeof(text), "%s, dt %g (%.2g ms)", integratorName(s.integrator),
                        s.dt, 1e3 * s.cpu_per_simulated_second);
          cells[r] = text;
        }
      }
      std::fprintf(md, "| %s | %g | %s | %s |\n", problem.c_str(), tolerance, cells[0].c_str(),
                   cells[1].c_str());
    }
  }
  std::fclose(csv);
  std::fclose(md);
}

}  // namespace
}  // namespace study
}  // namespace mass_aggregate_sim

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s OUTDIR\n", argv[0]);
    return 2;
  }
  const std::string dir = argv[1];
  using namespace mass_aggregate_sim::study;
  const std::vector<Sample> samples = workPrecision(dir);
  recommendations(dir, samples);
  stabilityMap(dir);
  energyDrift(dir);
  bodyStudy(dir);
  std::fprintf(stderr, "wrote CSV files to %s\n", dir.c_str());
  return 0;
}
