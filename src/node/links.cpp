#include "mass_aggregate_sim/node/links.h"

#include <algorithm>
#include <cmath>
#include <type_traits>
#include <utility>

#include "mass_aggregate_sim/node/input_limits.h"

namespace mass_aggregate_sim {
namespace node {
namespace {

using engine::GeneratorId;
using engine::ParticleId;
using engine::Real;
using engine::Result;
using engine::Status;
using engine::Vec3;

template <typename Generator>
bool containsId(const std::vector<Generator>& kind, const GeneratorId id) {
  return std::any_of(kind.begin(), kind.end(), [id](const Generator& g) { return g.id == id; });
}

// A negative length asks for the distance the link has when it is made.
Real lengthOrDistance(const Real requested, const Real distance) {
  return requested < 0.0 ? distance : requested;
}

Vec3 positionOf(const engine::World& world, const ParticleId id) {
  return world.particles().positions().col(*world.particles().find(id));
}

Result<GeneratorId> addAnchoredLink(engine::World& world, const ParticleId a,
                                    const LinkRequest& r) {
  const Status anchor = checkPosition(r.anchor, "anchor");
  if (!anchor) return anchor;
  const Real distance = (positionOf(world, a) - r.anchor).norm();
  switch (r.type) {
    case LinkType::kSpring:
      return world.addGenerator(engine::Spring::anchoredAt(
          a, r.anchor, r.stiffness, lengthOrDistance(r.rest_length, distance), r.damping));
    case LinkType::kBungee:
      return world.addGenerator(
          engine::Spring::anchoredAt(a, r.anchor, r.stiffness,
                                     lengthOrDistance(r.rest_length, distance), r.damping)
              .pullingOnly());
    case LinkType::kStiffSpring:
      return world.addGenerator(engine::StiffSpring{a, r.anchor, r.stiffness, r.damping});
    case LinkType::kCable:
      return world.addLink(engine::Cable::anchoredAt(
          a, r.anchor, lengthOrDistance(r.max_length, distance), r.restitution));
    case LinkType::kRod:
      return world.addLink(
          engine::Rod::anchoredAt(a, r.anchor, lengthOrDistance(r.length, distance)));
  }
  return Status::error("unknown link type");
}

Result<GeneratorId> addParticleLink(engine::World& world, const ParticleId a, const ParticleId b,
                                    const LinkRequest& r) {
  const Real distance = (positionOf(world, a) - positionOf(world, b)).norm();
  switch (r.type) {
    case LinkType::kSpring:
      return world.addGenerator(engine::Spring::between(
          a, b, r.stiffness, lengthOrDistance(r.rest_length, distance), r.damping));
    case LinkType::kBungee:
      return world.addGenerator(engine::Spring::between(a, b, r.stiffness,
                                                        lengthOrDistance(r.rest_length, distance),
                                                        r.damping)
                                    .pullingOnly());
    case LinkType::kStiffSpring:
      return Status::error("a stiff_spring links a particle to an anchor, not to particle b");
    case LinkType::kCable:
      return world.addLink(
          engine::Cable::between(a, b, lengthOrDistance(r.max_length, distance), r.restitution));
    case LinkType::kRod:
      return world.addLink(engine::Rod::between(a, b, lengthOrDistance(r.length, distance)));
  }
  return Status::error("unknown link type");
}

}  // namespace

Result<ParticleId> resolveParticle(const engine::World& world, const ParticleRef& ref) {
  if (!ref.name.empty()) {
    const auto id = world.particles().findByName(ref.name);
    if (!id) return Status::error("no particle named " + quoteInput(ref.name));
    return *id;
  }
  const ParticleId id = ParticleId::fromPacked(ref.id);
  if (!world.particles().contains(id)) {
    return Status::error("no particle with id " + std::to_string(ref.id) + " (" +
                         world.particles().describeInvalid(id) + ")");
  }
  return id;
}

std::optional<LinkType> parseLinkType(const std::string& name) {
  for (const LinkType type : {LinkType::kSpring, LinkType::kBungee, LinkType::kStiffSpring,
                              LinkType::kCable, LinkType::kRod}) {
    if (name == linkTypeName(type)) return type;
  }
  return std::nullopt;
}

const char* linkTypeName(const LinkType type) {
  switch (type) {
    case LinkType::kSpring:
      return "spring";
    case LinkType::kBungee:
      return "bungee";
    case LinkType::kStiffSpring:
      return "stiff_spring";
    case LinkType::kCable:
      return "cable";
    case LinkType::kRod:
      return "rod";
  }
  return "unknown";
}

std::string linkTypeNames() { return "spring, bungee, stiff_spring, cable, rod"; }

Status checkSpringNumbers(const Real stiffness, const Real damping) {
  const Status valid = checkNonNegative(stiffness, kMaxStiffness, "stiffness", "N/m");
  if (!valid) return valid;
  return checkNonNegative(damping, kMaxLinkDamping, "damping", "N s/m");
}

Status checkRequestedLength(const Real value, const char* field) {
  if (!std::isfinite(value)) return Status::error(std::string(field) + ": must be finite");
  if (value > kMaxLength) {
    return Status::error(std::string(field) + ": must be at most " + std::to_string(kMaxLength) +
                         " m (negative: the current distance)");
  }
  return Status::ok();
}

namespace {

// What the engine does not check itself: upper bounds, and lengths (negative: the distance).
Status checkLinkNumbers(const LinkRequest& r) {
  Status valid = checkSpringNumbers(r.stiffness, r.damping);
  if (valid) valid = checkRequestedLength(r.rest_length, "rest_length");
  if (valid) valid = checkRequestedLength(r.max_length, "max_length");
  if (valid) valid = checkRequestedLength(r.length, "length");
  return valid;
}

}  // namespace

Result<GeneratorId> addLink(engine::World& world, const LinkRequest& request) {
  const Status numbers = checkLinkNumbers(request);
  if (!numbers) return numbers;
  const auto a = resolveParticle(world, request.a);
  if (!a) return Status::error("a: " + a.message());
  if (!request.b) return addAnchoredLink(world, *a, request);
  const auto b = resolveParticle(world, *request.b);
  if (!b) return Status::error("b: " + b.message());
  return addParticleLink(world, *a, *b, request);
}

bool isLink(const engine::World& world, const GeneratorId id) {
  // Links are the generators drawn between two points (springs) and every link kind.
  bool found = false;
  world.generators().forEach([&](const auto& kind) {
    using Kind = typename std::decay_t<decltype(kind)>::value_type;
    if constexpr (engine::ForceKind<Kind>::kDrawn) found = found || containsId(kind, id);
  });
  world.links().forEach([&](const auto& kind) { found = found || containsId(kind, id); });
  return found || containsId(world.bodyGenerators().of<engine::PointSpring>(), id);
}

}  // namespace node
}  // namespace mass_aggregate_sim
