#pragma once
// Springs and bungees on bodies (the engine's PointSpring) as the node adds them, from a scene's
// forces and from ~add_body_spring.

#include <string>

#include "mass_aggregate_sim/engine/world/world.h"
#include "mass_aggregate_sim/node/joint_requests.h"

namespace mass_aggregate_sim {
namespace node {

struct BodySpringRequest {
  bool pull_only = false;  // a bungee
  JointEndRef a;
  JointEndRef b;
  // World points where the spring holds each end (a body keeps its point in its own frame, a
  // particle end is the particle, a world end is the point).
  engine::Vec3 anchor_a = engine::Vec3::Zero();
  engine::Vec3 anchor_b = engine::Vec3::Zero();
  engine::Real stiffness = 0.0;
  engine::Real damping = 0.0;
  engine::Real rest_length = -1.0;  // negative: the distance when it is added
};

// "spring" (pull_only false) or "bungee" (true); anything else is refused with both names.
engine::Result<bool> parseBodySpringType(const std::string& type);

// The node's bounds (checkSpringNumbers, checkRequestedLength), the ends resolved, then the
// engine's own checks; adds the spring or changes nothing.
engine::Result<engine::GeneratorId> addBodySpring(engine::World& world,
                                                  const BodySpringRequest& request);

}  // namespace node
}  // namespace mass_aggregate_sim
