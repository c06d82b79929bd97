// The rod kind (rod.h).
#include "mass_aggregate_sim/engine/solver/rod.h"

#include "engine/core/checks.h"
#include "engine/solver/link_checks.h"

namespace mass_aggregate_sim {
namespace engine {

Status LinkKind<Rod>::validate(Rod& rod, const ParticleStore& particles) {
  const Status ends = checkLinkEnds(rod, particles);
  if (!ends) return ends;
  if (!finitePositive(rod.length)) return Status::error("length must be finite and > 0");
  return Status::ok();
}

}  // namespace engine
}  // namespace mass_aggregate_sim
