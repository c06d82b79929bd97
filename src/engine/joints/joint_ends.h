#pragma once
// The check every end of a joint or of a spring on bodies passes when it is added.

#include <string>

#include "mass_aggregate_sim/engine/bodies/body_store.h"
#include "mass_aggregate_sim/engine/core/particle_store.h"
#include "mass_aggregate_sim/engine/joints/joint_kind.h"

namespace mass_aggregate_sim {
namespace engine {

// An end is a body or a particle (not both) or the world, its point finite, its body or particle
// live; with `turns` (a joint that holds rotation) it is not a particle, which has no orientation.
// `name` names the end in the refusal.
inline Status checkJointEnd(const JointEnd& end, const JointScene& scene, const char* name,
                            const bool turns) {
  if (end.isBody() && end.isParticle()) {
    return Status::error(std::string(name) + ": an end is a body or a particle, not both");
  }
  if (!end.point.allFinite()) return Status::error(std::string(name) + ": point is not finite");
  if (end.isBody()) return scene.bodies.checkReference(end.body, name);
  if (end.isParticle()) {
    if (turns) {
      return Status::error(std::string(name) +
                           ": a particle has no orientation for a joint that holds rotation");
    }
    return scene.particles.checkReference(end.particle, name);
  }
  return Status::ok();
}

}  // namespace engine
}  // namespace mass_aggregate_sim
