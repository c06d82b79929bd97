#pragma once

#include "mass_aggregate_sim/engine/integrator.h"
#include "mass_aggregate_sim/engine/status.h"
#include "mass_aggregate_sim/engine/types.h"

namespace mass_aggregate_sim {
namespace engine {

struct WorldConfig {
  Real dt = 1.0 / 60.0;  // fixed step, s
  int substeps = 1;      // each step is split into this many equal substeps
  Integrator integrator = Integrator::kSemiImplicitEuler;
  Vec3 gravity = Vec3::Zero();  // m/s^2, applied to every movable particle
  // advance(): longest frame time taken at once, so a stall does not cause a spiral of catch-up.
  Real max_frame_time = 0.25;
};

// dt finite and in (0, 1], substeps in [1, 1000], gravity finite, max_frame_time finite and >= dt.
Status validateConfig(const WorldConfig& config);

}  // namespace engine
}  // namespace mass_aggregate_sim
