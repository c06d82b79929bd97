#pragma once

#include <string>

namespace mass_aggregate_sim {
namespace study {

// The rigid-body half of the accuracy study (issue 14): every body problem (body_problems.h) at
// substeps 1, 2, 4, 8, iterations 1 to 8 and soft-constraint stiffness 0.5, 1 and 2 times the
// default, each against CPU time per simulated second. Writes into dir:
//   body_problems.csv         each problem's scene and what its metrics measure
//   body_work_precision.csv   one row per run and metric
//   body_recommendations.csv and body_recommendations.md   the cheapest settings per error level
void bodyStudy(const std::string& dir);

}  // namespace study
}  // namespace mass_aggregate_sim
