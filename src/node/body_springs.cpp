// Springs and bungees on bodies (body_springs.h).
#include "mass_aggregate_sim/node/body_springs.h"

#include <cmath>

#include "mass_aggregate_sim/node/input_limits.h"

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
  Status valid = checkNonNegative(request.stiffness, kMaxStiffness, "stiffness", "N/m");
  if (valid) valid = checkNonNegative(request.damping, kMaxLinkDamping, "damping", "N s/m");
  if (!valid) return valid;
  if (!std::isfinite(request.rest_length) || request.rest_length > kMaxLength) {
    return Status::error("rest_length: must be finite and at most " + std::to_string(kMaxLength) +
                         " m (negative: the distance now)");
  }
  const auto a = resolveJointEnd(world, request.a, request.anchor_a, "a");
  if (!a) return a.status();
  const auto b = resolveJointEnd(world, request.b, request.anchor_b, "b");
  if (!b) return b.status();
  engine::PointSpring spring = engine::PointSpring::between(
      *a, *b, request.stiffness, request.rest_length < 0.0 ? -1.0 : request.rest_length,
      request.damping);
  spring.pull_only = request.pull_only;
  return world.addBodyGenerator(spring);
}

}  // namespace node
}  // namespace mass_aggregate_sim
