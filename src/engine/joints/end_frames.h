#pragma once
// Where a joint end is now: its point in the world, and how its mass frame is turned (a body's
// orientation; the world's and a particle's identity).

#include "mass_aggregate_sim/engine/bodies/body_store.h"
#include "mass_aggregate_sim/engine/core/particle_store.h"
#include "mass_aggregate_sim/engine/joints/joint_kind.h"

namespace mass_aggregate_sim {
namespace engine {

inline Quat endOrientation(const JointEnd& end, const BodyStore& bodies) {
  if (!end.isBody()) return Quat::Identity();
  return bodies.orientation(bodies.denseIndexUnchecked(end.body));
}

inline Vec3 endPosition(const JointEnd& end, const JointScene& scene) {
  if (end.isBody()) {
    return scene.bodies.pose(scene.bodies.denseIndexUnchecked(end.body)).apply(end.point);
  }
  if (end.isParticle()) {
    return scene.particles.positions().col(scene.particles.denseIndexUnchecked(end.particle));
  }
  return end.point;
}

}  // namespace engine
}  // namespace mass_aggregate_sim
