#include "mass_aggregate_sim/engine/world/world_config.h"

#include <cmath>

namespace mass_aggregate_sim {
namespace engine {

Status validateConfig(const WorldConfig& config) {
  if (!std::isfinite(config.dt) || config.dt <= 0.0 || config.dt > 1.0) {
    return Status::error("dt must be finite and in (0, 1] s");
  }
  if (config.substeps < 1 || config.substeps > 1000) {
    return Status::error("substeps must be in [1, 1000]");
  }
  if (!config.gravity.allFinite()) return Status::error("gravity must be finite");
  if (!std::isfinite(config.max_frame_time) || config.max_frame_time < config.dt) {
    return Status::error("max_frame_time must be finite and >= dt");
  }
  if (!std::isfinite(config.energy_growth_limit) || config.energy_growth_limit < 0.0) {
    return Status::error("energy_growth_limit must be finite and >= 0 (0 = energy guard off)");
  }
  return Status::ok();
}

}  // namespace engine
}  // namespace mass_aggregate_sim
