#pragma once
// gtest parameters over every integrator, named by integratorName().

#include <gtest/gtest.h>

#include <string>

#include "mass_aggregate_sim/engine/integrators/integrator.h"

namespace mass_aggregate_sim {
namespace engine {

inline auto everyIntegrator() { return ::testing::ValuesIn(allIntegrators()); }

inline std::string integratorParamName(const ::testing::TestParamInfo<Integrator>& info) {
  return integratorName(info.param);
}

}  // namespace engine
}  // namespace mass_aggregate_sim
