#pragma once
// Drag and buoyancy on particles and bodies (the engine's Drag, Buoyancy, BodyDrag and
// BodyBuoyancy) as ~add_force_field adds them, and the names of the bodies' buoyancy models that
// the scenes share.

#include <string>
#include <vector>

#include "mass_aggregate_sim/engine/world/world.h"
#include "mass_aggregate_sim/node/body_requests.h"
#include "mass_aggregate_sim/node/links.h"

namespace mass_aggregate_sim {
namespace node {

enum class ForceFieldType { kDrag, kBuoyancy };

struct ForceFieldRequest {
  ForceFieldType type = ForceFieldType::kDrag;
  std::vector<ParticleRef> particles;
  std::vector<BodyRef> bodies;
  engine::Real k1 = 0.0;
  engine::Real k2 = 0.0;
  engine::Real angular = 0.0;
  engine::BuoyancyModel model = engine::BuoyancyModel::kShapes;
  engine::Real volume = 0.0;
  engine::Real max_depth = 0.0;  // <= 0 on a body: the engine's default (its reach, or none)
  engine::Real liquid_density = 0.0;
  // The surface in the world: up.x = surface_height.
  engine::Real surface_height = 0.0;
  engine::Vec3 up = engine::Vec3::UnitZ();
};

// "drag" or "buoyancy"; anything else is refused with both names.
engine::Result<ForceFieldType> parseForceFieldType(const std::string& type);
// "shapes" (also "", the default) or "centre".
engine::Result<engine::BuoyancyModel> parseBuoyancyModel(const std::string& model);

// One generator on each particle, then each body, of the request, all or none: every target is
// resolved first, and should the engine refuse one after others were added, those are removed
// again. The message of a refusal names the target.
engine::Result<std::vector<engine::GeneratorId>> addForceFields(engine::World& world,
                                                                const ForceFieldRequest& request);

// Whether id is a drag or a buoyancy (on a particle or a body).
bool isForceField(const engine::World& world, engine::GeneratorId id);

}  // namespace node
}  // namespace mass_aggregate_sim
