#pragma once

#include <cstdint>
#include <utility>

#include "mass_aggregate_sim/engine/core/types.h"
#include "mass_aggregate_sim/engine/forces/force_generators.h"

namespace mass_aggregate_sim {
namespace engine {

enum class ContactKind : std::uint8_t {
  kContact,  // overlap with a collider or another particle: pushes only
  kCable,    // a taut cable: pulls only
  kRod,      // a rod: pushes or pulls to hold its length
};

// Dense index meaning "no second particle": the contact is against a collider or an anchor.
constexpr std::uint32_t kNoParticle = 0xFFFFFFFFu;

// One constraint for the resolver. An impulse j acts as +j n on a and -j n on b, so the
// separating velocity is v_sep = (v_a - v_b).n and v_sep < 0 means the violation is growing.
// 72 bytes: what only links need is in their LinkGeometry.
struct Contact {
  std::uint32_t a = kNoParticle;
  std::uint32_t b = kNoParticle;
  ContactKind kind = ContactKind::kContact;
  // A collider a little beyond reach (a gap wider than the contact margin): no impulse, no
  // statistics; the position passes push the particle back out if other contacts' corrections
  // move it into the collider within the substep.
  bool position_only = false;
  // Two particles of a pile that rests on moving bodies alone: the body solver takes the
  // contact's velocities (normal and friction); the positions stage here still takes out its
  // overlap (bodies/particle_pair.h).
  bool body_solved = false;
  std::uint32_t link = 0;  // links: index of their LinkGeometry
  Vec3 normal = Vec3::UnitZ();
  // How far a must move along normal (relative to b) to satisfy the constraint; links recompute it
  // from the positions, contacts track it as penetration - (dx_a - dx_b).n.
  Real penetration = 0.0;
  Real restitution = 0.0;
  Real friction = 0.0;
  // Names the same contact in the next substep, so it can start from this one's impulse:
  // contactKey() of its particles' slots, collider or link.
  std::uint64_t key = 0;

  // Whether the particle solver's velocity phase takes it (impulses, friction), not only its
  // positions stage.
  bool solvesVelocities() const { return !position_only && !body_solved; }
};

// What a link constraint needs beyond its Contact.
struct LinkGeometry {
  Vec3 anchor = Vec3::Zero();  // anchored links: the fixed end
  Real length = 0.0;           // the rod length or the cable's maximum
};

// Keys: particle pairs by their two slots, particle-collider by slot and collider id, links by id,
// particle-body surface (ContactWorkspace::BodySurface) by slot and body shape.
inline std::uint64_t pairContactKey(std::uint32_t slot_a, std::uint32_t slot_b) {
  if (slot_a > slot_b) std::swap(slot_a, slot_b);
  return (std::uint64_t{slot_a} << 31) ^ slot_b;
}
inline std::uint64_t colliderContactKey(const std::uint32_t slot, const std::uint32_t collider) {
  return (std::uint64_t{1} << 62) | ((std::uint64_t{slot} << 31) ^ collider);
}
inline std::uint64_t linkContactKey(const std::uint32_t link) {
  return (std::uint64_t{2} << 62) | link;
}
inline std::uint64_t stillSurfaceContactKey(const std::uint32_t slot, const std::uint32_t shape) {
  return (std::uint64_t{3} << 62) | ((std::uint64_t{slot} << 31) ^ shape);
}
// A moving body's surface is position-only: never an impulse the report could mistake for the
// body rows'.
inline std::uint64_t movingSurfaceContactKey(const std::uint32_t slot, const std::uint32_t shape) {
  return stillSurfaceContactKey(slot, shape) ^ (std::uint64_t{1} << 61);
}

}  // namespace engine
}  // namespace mass_aggregate_sim
