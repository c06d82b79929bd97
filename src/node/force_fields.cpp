// Drag and buoyancy on particles and bodies (force_fields.h).
#include "mass_aggregate_sim/node/force_fields.h"

#include <variant>

#include "mass_aggregate_sim/node/input_limits.h"

namespace mass_aggregate_sim {
namespace node {

using engine::GeneratorId;
using engine::Result;
using engine::Status;

Result<ForceFieldType> parseForceFieldType(const std::string& type) {
  if (type == "drag") return ForceFieldType::kDrag;
  if (type == "buoyancy") return ForceFieldType::kBuoyancy;
  return Status::error("type: unknown force field " + quoteInput(type) +
                       " (known: drag, buoyancy)");
}

Result<engine::BuoyancyModel> parseBuoyancyModel(const std::string& model) {
  if (model.empty() || model == "shapes") return engine::BuoyancyModel::kShapes;
  if (model == "centre") return engine::BuoyancyModel::kCentre;
  return Status::error("unknown model " + quoteInput(model) + " (known: shapes, centre)");
}

namespace {

// The request's liquid on a particle's or a body's buoyancy.
template <typename Buoyancy>
void pourLiquid(const ForceFieldRequest& r, Buoyancy& buoyancy) {
  buoyancy.volume = r.volume;
  buoyancy.liquid_density = r.liquid_density;
  buoyancy.surface_height = r.surface_height;
  buoyancy.up = r.up;
}

// The generator of the request's type on one particle or one body.
std::variant<engine::Drag, engine::Buoyancy> onParticle(const ForceFieldRequest& r,
                                                        const engine::ParticleId id) {
  if (r.type == ForceFieldType::kDrag) return engine::Drag{id, r.k1, r.k2};
  engine::Buoyancy buoyancy;
  buoyancy.particle = id;
  buoyancy.max_depth = r.max_depth;
  pourLiquid(r, buoyancy);
  return buoyancy;
}

std::variant<engine::BodyDrag, engine::BodyBuoyancy> onBody(const ForceFieldRequest& r,
                                                            const engine::BodyId id) {
  if (r.type == ForceFieldType::kDrag) {
    engine::BodyDrag drag;
    drag.body = id;
    drag.k1 = r.k1;
    drag.k2 = r.k2;
    drag.angular = r.angular;
    return drag;
  }
  engine::BodyBuoyancy buoyancy;
  buoyancy.body = id;
  buoyancy.model = r.model;
  // 0 or less asks for the default; NaN goes on to be refused.
  buoyancy.max_depth = r.max_depth <= 0.0 ? -1.0 : r.max_depth;
  pourLiquid(r, buoyancy);
  return buoyancy;
}

// The generators `make` gives for each of `refs` (resolved by `resolve`), each checked by
// `check`; the first refusal, named by `field` and the target's index.
template <typename Refs, typename Resolve, typename Make, typename Check, typename Generators>
Status prepare(const Refs& refs, const char* field, Resolve&& resolve, Make&& make, Check&& check,
               Generators& out) {
  for (std::size_t k = 0; k < refs.size(); ++k) {
    const std::string where = std::string(field) + "[" + std::to_string(k) + "]: ";
    const auto id = resolve(refs[k]);
    if (!id) return Status::error(where + id.message());
    out.push_back(make(*id));
    const Status valid = std::visit(check, out.back());
    if (!valid) return Status::error(where + valid.message());
  }
  return Status::ok();
}

}  // namespace

Result<std::vector<GeneratorId>> addForceFields(engine::World& world,
                                                const ForceFieldRequest& request) {
  if (request.particles.empty() && request.bodies.empty()) {
    return Status::error("name at least one particle or body");
  }
  std::vector<std::variant<engine::Drag, engine::Buoyancy>> on_particles;
  const Status particles = prepare(
      request.particles, "particles",
      [&](const ParticleRef& r) { return resolveParticle(world, r); },
      [&](const engine::ParticleId id) { return onParticle(request, id); },
      [&](const auto& g) { return world.checkGenerator(g); }, on_particles);
  if (!particles) return particles;
  std::vector<std::variant<engine::BodyDrag, engine::BodyBuoyancy>> on_bodies;
  const Status bodies = prepare(
      request.bodies, "bodies", [&](const BodyRef& r) { return resolveBody(world, r); },
      [&](const engine::BodyId id) { return onBody(request, id); },
      [&](const auto& g) { return world.checkBodyGenerator(g); }, on_bodies);
  if (!bodies) return bodies;
  // Every one checked: the engine takes each as it said it would.
  std::vector<GeneratorId> ids;
  for (const auto& generator : on_particles) {
    ids.push_back(*std::visit([&](const auto& g) { return world.addGenerator(g); }, generator));
  }
  for (const auto& generator : on_bodies) {
    ids.push_back(*std::visit([&](const auto& g) { return world.addBodyGenerator(g); }, generator));
  }
  return ids;
}

bool isForceField(const engine::World& world, const GeneratorId id) {
  const auto in = [id](const auto& kind) {
    for (const auto& g : kind) {
      if (g.id == id) return true;
    }
    return false;
  };
  return in(world.generators().of<engine::Drag>()) ||
         in(world.generators().of<engine::Buoyancy>()) ||
         in(world.bodyGenerators().of<engine::BodyDrag>()) ||
         in(world.bodyGenerators().of<engine::BodyBuoyancy>());
}

}  // namespace node
}  // namespace mass_aggregate_sim
