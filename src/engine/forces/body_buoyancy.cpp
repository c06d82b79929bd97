// The body buoyancy kind (body_buoyancy.h): validation (the body's volume and reach when not
// given) and force.
#include "mass_aggregate_sim/engine/forces/body_buoyancy.h"

#include <cmath>
#include <type_traits>
#include <variant>

#include "engine/core/checks.h"
#include "engine/forces/body_force_stage.h"
#include "engine/forces/force_laws.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

Real shapesVolume(const BodyStore& bodies, const std::size_t i) {
  Real volume = 0.0;
  for (const ShapeIndex s : bodies.shapesOf(i)) {
    std::visit(
        [&](const auto& g) { volume += BodyShapeKind<std::decay_t<decltype(g)>>::volume(g); },
        bodies.shapes()[s].geometry);
  }
  return volume;
}

}  // namespace

Status BodyForceKind<BodyBuoyancy>::validate(BodyBuoyancy& buoyancy, const JointScene& scene) {
  const Status body = scene.bodies.checkReference(buoyancy.body, "body");
  if (!body) return body;
  if (!std::isfinite(buoyancy.volume)) return Status::error("volume is not finite");
  if (!std::isfinite(buoyancy.max_depth)) return Status::error("max_depth is not finite");
  if (buoyancy.max_depth == 0.0) return Status::error("max_depth must be > 0 (or < 0: the reach)");
  const Status liquid = checkLiquid(buoyancy.liquid_density, buoyancy.surface_height, buoyancy.up);
  if (!liquid) return liquid;
  const std::size_t i = scene.bodies.denseIndexUnchecked(buoyancy.body);
  buoyancy.up.normalize();
  if (buoyancy.volume <= 0.0) buoyancy.volume = shapesVolume(scene.bodies, i);
  if (buoyancy.max_depth < 0.0) buoyancy.max_depth = scene.bodies.reach(i);
  return Status::ok();
}

void BodyForceKind<BodyBuoyancy>::accumulate(const std::vector<BodyBuoyancy>& buoyancies,
                                             const BodyForceScene& scene, BodyForceSums& sums) {
  for (const BodyBuoyancy& buoyancy : buoyancies) {
    const ForceEnd centre = scene.centre(buoyancy.body);
    const Real height = buoyancy.up.dot(centre.position) - buoyancy.surface_height;
    const Real submerged = submergedFraction(height, buoyancy.max_depth);
    if (submerged == 0.0) continue;
    const Real full = buoyancy.liquid_density * buoyancy.volume * scene.gravityMagnitude();
    sums.add(centre, full * submerged * buoyancy.up);
  }
}

}  // namespace engine
}  // namespace mass_aggregate_sim
