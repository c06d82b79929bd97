#pragma once
// The checks both link kinds make of their ends.

#include "mass_aggregate_sim/engine/core/particle_store.h"

namespace mass_aggregate_sim {
namespace engine {

// Live distinct particles, or a live particle and a finite anchor.
template <typename Link>
Status checkLinkEnds(const Link& link, const ParticleStore& particles) {
  if (link.anchored()) {
    const Status particle = particles.checkReference(link.a, "particle");
    if (!particle) return particle;
    if (!link.anchor.allFinite()) return Status::error("anchor is not finite");
    return Status::ok();
  }
  Status end = particles.checkReference(link.a, "a");
  if (end) end = particles.checkReference(link.b, "b");
  if (end && link.a == link.b) end = Status::error("a and b must be different particles");
  return end;
}

}  // namespace engine
}  // namespace mass_aggregate_sim
