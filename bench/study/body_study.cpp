#include "body_study.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "body_problems.h"
#include "study_io.h"

namespace mass_aggregate_sim {
namespace study {
namespace {

const int kSubsteps[] = {1, 2, 4, 8};
constexpr int kMaxIterations = 8;
const Real kStiffness[] = {0.5, 1.0, 2.0};

struct BodySample {
  const BodyProblem* problem;
  BodyKnobs knobs;
  BodyRun run;
  Real cpu_per_simulated_second;
};

// Every problem at every knob setting, each run repeated until kMinimumCpuSeconds of CPU time
// are measured.
std::vector<BodySample> sweep(const std::vector<BodyProblem>& problems) {
  std::vector<BodySample> samples;
  for (const BodyProblem& problem : problems) {
    const double problem_start = cpuSeconds();
    for (const Real stiffness : kStiffness) {
      for (const int substeps : kSubsteps) {
        for (int iterations = 1; iterations <= kMaxIterations; ++iterations) {
          const BodyKnobs knobs{substeps, iterations, stiffness};
          BodyRun run;
          int runs = 0;
          const double start = cpuSeconds();
          double elapsed = 0.0;
          do {
            run = problem.run(knobs);
            ++runs;
            elapsed = cpuSeconds() - start;
          } while (elapsed < kMinimumCpuSeconds);
          samples.push_back({&problem, knobs, run, elapsed / runs / problem.duration});
        }
      }
    }
    std::fprintf(stderr, "body work-precision: %s (%.1f s CPU)\n", problem.name.c_str(),
                 cpuSeconds() - problem_start);
  }
  return samples;
}

// What each problem is and what each of its metrics measures, for the docs' table.
void describeProblems(const std::vector<BodyProblem>& problems, const std::string& dir) {
  FILE* csv = openCsv(dir, "body_problems.csv", "problem,duration_s,scene,metric,measures");
  for (const BodyProblem& problem : problems) {
    for (const BodyMetric& metric : problem.metrics) {
      std::fprintf(csv, "%s,%g,\"%s\",%s,\"%s\"\n", problem.name.c_str(), problem.duration,
                   problem.description.c_str(), metric.name.c_str(), metric.description.c_str());
    }
  }
  std::fclose(csv);
}

// One row per run and metric, a metric's rows together (in the sweep's order: stiffness, then
// substeps, then iterations), so that a plot's line through them is not broken by other rows.
void writeSamples(const std::vector<BodyProblem>& problems, const std::vector<BodySample>& samples,
                  const std::string& dir) {
  FILE* csv = openCsv(dir, "body_work_precision.csv",
                      "problem,metric,substeps,iterations,stiffness,contact_hz,joint_hz,value,"
                      "cpu_s_per_simulated_s,diverged");
  for (const BodyProblem& problem : problems) {
    for (std::size_t m = 0; m < problem.metrics.size(); ++m) {
      for (const BodySample& s : samples) {
        if (s.problem != &problem) continue;
        std::fprintf(csv, "%s,%s,%d,%d,%g,%g,%g,%.6e,%.6e,%d\n", problem.name.c_str(),
                     problem.metrics[m].name.c_str(), s.knobs.substeps, s.knobs.iterations,
                     s.knobs.stiffness, contactHertz(s.knobs), jointHertz(s.knobs), s.run.values[m],
                     s.cpu_per_simulated_second, s.run.diverged ? 1 : 0);
      }
    }
  }
  std::fclose(csv);
}

// The run with the fewest iterations from which on every count up to 8 reaches the tolerance on
// metric m, at one substep count and stiffness (some metrics scatter from one count to the next);
// null when the 8th does not. Samples are in the sweep's order, iterations rising.
const BodySample* steadilyWithin(const std::vector<BodySample>& samples, const BodyProblem& problem,
                                 const std::size_t m, const Real tolerance, const int substeps,
                                 const Real stiffness) {
  const BodySample* first = nullptr;
  for (auto it = samples.rbegin(); it != samples.rend(); ++it) {
    if (it->problem != &problem || it->knobs.substeps != substeps ||
        it->knobs.stiffness != stiffness) {
      continue;
    }
    if (it->run.diverged || !(std::abs(it->run.values[m]) <= tolerance)) break;
    first = &*it;
  }
  return first;
}

// Fewer iterations first, then the default stiffness, then the cheaper. Iterations are compared
// by count, not by measured time, so that timing noise between neighbours cannot pick more passes.
bool preferred(const BodySample& a, const BodySample& b) {
  if (a.knobs.iterations != b.knobs.iterations) return a.knobs.iterations < b.knobs.iterations;
  if ((a.knobs.stiffness == 1.0) != (b.knobs.stiffness == 1.0)) return a.knobs.stiffness == 1.0;
  return a.cpu_per_simulated_second < b.cpu_per_simulated_second;
}

// For each problem, metric with tolerances and tolerance: per substep count the preferred of the
// stiffnesses' steadilyWithin runs, then those ranked by CPU time.
void recommendations(const std::vector<BodyProblem>& problems,
                     const std::vector<BodySample>& samples, const std::string& dir) {
  FILE* csv = openCsv(dir, "body_recommendations.csv",
                      "problem,metric,tolerance,rank,substeps,iterations,stiffness,value,"
                      "cpu_s_per_simulated_s");
  FILE* md = std::fopen((dir + "/body_recommendations.md").c_str(), "w");
  std::fprintf(md,
               "| problem | metric | error at most | best: substeps x iterations, stiffness (CPU "
               "per simulated s; error) | runner-up |\n|---|---|---|---|---|\n");
  for (const BodyProblem& problem : problems) {
    for (std::size_t m = 0; m < problem.metrics.size(); ++m) {
      for (const Real tolerance : problem.metrics[m].tolerances) {
        std::vector<const BodySample*> best;
        for (const int substeps : kSubsteps) {
          const BodySample* chosen = nullptr;
          for (const Real stiffness : kStiffness) {
            const BodySample* s =
                steadilyWithin(samples, problem, m, tolerance, substeps, stiffness);
            if (s && (!chosen || preferred(*s, *chosen))) chosen = s;
          }
          if (chosen) best.push_back(chosen);
        }
        std::sort(best.begin(), best.end(), [](const BodySample* a, const BodySample* b) {
          return a->cpu_per_simulated_second < b->cpu_per_simulated_second;
        });
        std::string cells[2] = {"none in the sweep", "-"};
        for (std::size_t r = 0; r < best.size(); ++r) {
          const BodySample& s = *best[r];
          std::fprintf(csv, "%s,%s,%g,%zu,%d,%d,%g,%.3e,%.3e\n", problem.name.c_str(),
                       problem.metrics[m].name.c_str(), tolerance, r + 1, s.knobs.substeps,
                       s.knobs.iterations, s.knobs.stiffness, s.run.values[m],
                       s.cpu_per_simulated_second);
          if (r < 2) {
            char text[160];
            std::snprintf(text, sizeof(text), "%d x %d, %gx (%.2g ms; %.1e)", s.knobs.substeps,
                          s.knobs.iterations, s.knobs.stiffness, 1e3 * s.cpu_per_simulated_second,
                          s.run.values[m]);
            cells[r] = text;
          }
        }
        std::fprintf(md, "| %s | %s | %g | %s | %s |\n", problem.name.c_str(),
                     problem.metrics[m].name.c_str(), tolerance, cells[0].c_str(),
                     cells[1].c_str());
      }
    }
  }
  std::fclose(csv);
  std::fclose(md);
}

}  // namespace

void bodyStudy(const std::string& dir) {
  const std::vector<BodyProblem> problems = {
      hingedPendulum(), weldedPendulum(), torqueFreeTumble(), cubeStack(),
      droppedStack(),   turnedStack(),    heavyLightStack(),  cubeBounce()};
  const std::vector<BodySample> samples = sweep(problems);
  describeProblems(problems, dir);
  writeSamples(problems, samples, dir);
  recommendations(problems, samples, dir);
}

}  // namespace study
}  // namespace mass_aggregate_sim
