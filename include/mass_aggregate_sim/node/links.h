#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "mass_aggregate_sim/engine/world/world.h"

namespace mass_aggregate_sim {
namespace node {

// Names a particle in a request: by name when the name is non-empty, otherwise by packed id.
struct ParticleRef {
  std::uint64_t id = 0;
  std::string name;
};

engine::Result<engine::ParticleId> resolveParticle(const engine::World& world,
                                                   const ParticleRef& ref);

enum class LinkType { kSpring, kBungee, kStiffSpring, kCable, kRod };
std::optional<LinkType> parseLinkType(const std::string& name);
const char* linkTypeName(LinkType type);
// All names, comma separated, for error messages.
std::string linkTypeNames();

// The node's bounds on a spring's numbers, for links and springs on bodies alike: stiffness in
// [0, kMaxStiffness] N/m, damping in [0, kMaxLinkDamping] N s/m; and a requested length (a
// rest_length, max_length or length) finite and at most kMaxLength (negative: the distance now).
engine::Status checkSpringNumbers(engine::Real stiffness, engine::Real damping);
engine::Status checkRequestedLength(engine::Real value, const char* field);

// A link between particle a and particle b, or between a and a fixed anchor when b is empty.
// A negative rest_length / max_length / length means the distance when the link is made.
struct LinkRequest {
  LinkType type = LinkType::kSpring;
  ParticleRef a;
  std::optional<ParticleRef> b;
  engine::Vec3 anchor = engine::Vec3::Zero();
  engine::Real stiffness = 0.0;
  engine::Real damping = 0.0;
  engine::Real rest_length = -1.0;
  engine::Real max_length = -1.0;
  engine::Real length = -1.0;
  engine::Real restitution = 0.0;
};

// Validates the request against the world and adds the link, or changes nothing.
engine::Result<engine::GeneratorId> addLink(engine::World& world, const LinkRequest& request);
// Whether the generator id names a link (not a drag or buoyancy).
bool isLink(const engine::World& world, engine::GeneratorId id);

}  // namespace node
}  // namespace mass_aggregate_sim
