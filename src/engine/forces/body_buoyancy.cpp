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

// The part of body i's shapes below the surface, its mass frame at `pose`.
SubmergedVolume shapesBelow(const BodyStore& bodies, const std::size_t i, const Transform& pose,
                            const LiquidSurface& surface) {
  SubmergedVolume sum;
  for (const ShapeIndex s : bodies.shapesOf(i)) {
    const BodyShape& shape = bodies.shapes()[s];
    const Frame frame(pose * shape.local);
    std::visit(
        [&](const auto& g) {
          sum += BodyShapeKind<std::decay_t<decltype(g)>>::submerged(g, frame, surface);
        },
        shape.geometry);
  }
  return sum;
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
  switch (buoyancy.model) {
    case BuoyancyModel::kShapes:
      if (buoyancy.max_depth > 0.0) {
        return Status::error(
            "max_depth is for model centre: model shapes finds the submerged part of the shapes");
      }
      break;
    case BuoyancyModel::kCentre:
      break;
    default:
      return Status::error("model must be shapes or centre");
  }
  const std::size_t i = scene.bodies.denseIndexUnchecked(buoyancy.body);
  buoyancy.up.normalize();
  if (buoyancy.volume <= 0.0) buoyancy.volume = shapesVolume(scene.bodies, i);
  if (buoyancy.model == BuoyancyModel::kCentre && buoyancy.max_depth < 0.0) {
    buoyancy.max_depth = scene.bodies.reach(i);
  }
  return Status::ok();
}

void BodyForceKind<BodyBuoyancy>::accumulate(const std::vector<BodyBuoyancy>& buoyancies,
                                             const BodyForceScene& scene, BodyForceSums& sums) {
  for (const BodyBuoyancy& buoyancy : buoyancies) {
    ForceEnd centre = scene.centre(buoyancy.body);
    const Real full = buoyancy.liquid_density * buoyancy.volume * scene.gravityMagnitude();
    switch (buoyancy.model) {
      case BuoyancyModel::kShapes: {
        const std::size_t i = scene.bodies().denseIndexUnchecked(buoyancy.body);
        const LiquidSurface surface{buoyancy.up, buoyancy.surface_height};
        const SubmergedVolume part =
            shapesBelow(scene.bodies(), i, scene.massPose(buoyancy.body), surface);
        if (part.volume <= 0.0) break;
        const Real shapes = shapesVolume(scene.bodies(), i);
        centre.r = part.moment / part.volume - centre.position;
        sums.add(centre, full * (part.volume / shapes) * buoyancy.up);
        break;
      }
      case BuoyancyModel::kCentre: {
        const Real height = buoyancy.up.dot(centre.position) - buoyancy.surface_height;
        const Real submerged = submergedFraction(height, buoyancy.max_depth);
        if (submerged > 0.0) sums.add(centre, full * submerged * buoyancy.up);
        break;
      }
    }
  }
}

}  // namespace engine
}  // namespace mass_aggregate_sim
