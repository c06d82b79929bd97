// The accuracy study's rod problems (docs/ACCURACY.md) measured two ways at once: the largest
// error over the run (what the study reports since session 35) and the error at the end alone
// (what it reported before), at two steps of the sweep and at the frame rate users run, 1/60 s.
// Build and run from the repository root after scripts/accuracy_study.sh has built the engine:
//   g++ -std=c++17 -O2 -I include -I bench/study -I /usr/include/eigen3 \
//     docs/benchmarks/trajectory_error_probe.cpp bench/study/reference_problems.cpp \
//     bench/study/link_problems.cpp -o /tmp/trajectory_error_probe \
//     -L ~/mass_aggregate_sim_ws/devel/lib -lmass_aggregate_sim_engine \
//     -Wl,-rpath,$HOME/mass_aggregate_sim_ws/devel/lib
//   /tmp/trajectory_error_probe
// Output on 2026-11-30 (2c6dfa8's engine):
//   rod_pendulum dt 0.2000 semi_implicit_euler: largest 1.680e+00 at the end 7.852e-01
//   rod_pendulum dt 0.2000 velocity_verlet: largest 1.160e+00 at the end 1.136e+00
//   rod_pendulum dt 0.1000 semi_implicit_euler: largest 8.163e-01 at the end 1.863e-01
//   rod_pendulum dt 0.1000 velocity_verlet: largest 1.296e+00 at the end 1.296e+00
//   rod_pendulum dt 0.0167 semi_implicit_euler: largest 3.020e-02 at the end 6.706e-03
//   rod_pendulum dt 0.0167 velocity_verlet: largest 6.838e-03 at the end 6.318e-04
//   rod_rope dt 0.2000 semi_implicit_euler: largest 3.944e+00 at the end 3.944e+00
//   rod_rope dt 0.2000 velocity_verlet: largest 3.586e+00 at the end 2.574e+00
//   rod_rope dt 0.1000 semi_implicit_euler: largest 8.106e-01 at the end 6.132e-01
//   rod_rope dt 0.1000 velocity_verlet: largest 1.578e+00 at the end 1.390e+00
//   rod_rope dt 0.0167 semi_implicit_euler: largest 1.035e-01 at the end 7.805e-02
//   rod_rope dt 0.0167 velocity_verlet: largest 3.254e-02 at the end 2.105e-02
#include <algorithm>
#include <cstdio>

#include "reference_problems.h"

using mass_aggregate_sim::engine::Integrator;
using mass_aggregate_sim::engine::integratorName;
using namespace mass_aggregate_sim::study;

double largestError(const Trajectory& run, const Trajectory& reference, const std::size_t from) {
  double worst = 0.0;
  for (std::size_t k = from; k < run.size(); ++k) {
    for (Eigen::Index i = 0; i < run[k].cols(); ++i) {
      worst = std::max(worst, (run[k].col(i) - reference[k].col(i)).norm());
    }
  }
  return worst;
}

int main() {
  for (const ReferenceProblem& problem : {rodPendulum(), rodRope()}) {
    const Trajectory reference = referenceTrajectory(problem);
    for (const double dt : {0.2, 0.1, 1.0 / 60.0}) {
      for (const Integrator integrator :
           {Integrator::kSemiImplicitEuler, Integrator::kVelocityVerlet}) {
        const Trajectory run = trajectory(problem, integrator, dt);
        std::printf("%s dt %.4f %s: largest %.3e at the end %.3e\n", problem.name.c_str(), dt,
                    integratorName(integrator), largestError(run, reference, 0),
                    largestError(run, reference, run.size() - 1));
      }
    }
  }
  return 0;
}
