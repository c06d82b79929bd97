// Springs and bungees on bodies (body_springs.h).
#include "mass_aggregate_sim/node/body_springs.h"

#include "mass_aggregate_sim/node/input_limits.h"
#include "mass_aggregate_sim/node/links.h"

namespace mass_aggregate_sim {
namespace node {

using engine::Real;
using engine::Result;
using engine::Status;

Result<bool> parseBodySpringType(const std::string& type) {
  if (type == "spring") return false;
  if (type == "bungee") return true;
  return Status::error("type: unknown body spring type " + quoteInput(type) +
                       " (known: spring, bungee)");
}

Result<engine::GeneratorId> addBodySpring(engine::World& world, const BodySpringRequest& request) {
  Status valid = checkSpringNumbers(request.stiffness, request.damping);
  if (valid) valid = checkRequestedLength(request.rest_length, "rest_length");
  if (!valid) return valid;
  const auto a = resolveJointEnd(world, request.a, request.anchor_a, "a");
  if (!a) return a.status();
  const auto b = resolveJointEnd(world, request.b, request.anchor_b, "b");
  if (!b) return b.status();
  engine::PointSpring spring =
      engine::PointSpring::between(*a, *b, request.stiffness, request.rest_length, request.damping);
  spring.pull_only = request.pull_only;
  return world.addBodyGenerator(spring);
}

}  // namespace node
}  // namespace mass_aggregate_sim
