// The cable kind (cable.h).
#include "mass_aggregate_sim/engine/solver/cable.h"

#include <cmath>

#include "engine/core/checks.h"
#include "engine/solver/link_checks.h"

namespace mass_aggregate_sim {
namespace engine {

Status LinkKind<Cable>::validate(Cable& cable, const ParticleStore& particles) {
  const Status ends = checkLinkEnds(cable, particles);
  if (!ends) return ends;
  if (!finitePositive(cable.max_length)) return Status::error("max_length must be finite and > 0");
  if (!std::isfinite(cable.restitution) || cable.restitution < 0.0 || cable.restitution > 1.0) {
    return Status::error("restitution must be in [0, 1]");
  }
  return Status::ok();
}

}  // namespace engine
}  // namespace mass_aggregate_sim
