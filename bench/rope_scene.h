#pragma once
// A rope of rods or cables, shared by its benchmark (bench/links_bench.cpp) and its engine tests
// (test/engine/solver/links_test.cpp, test/engine/world/energy_guard_test.cpp), so all run the
// same rope: `knots` particles, 1 kg in all, on as many links of 1 m / knots from an anchor at the
// origin, laid out along `direction` (released from the horizontal, or hanging when it points
// down), knots of the given radius; or tied between two anchors (tie()). Particle collisions are
// the caller's; even without them the radius orders the passes (rows are sorted by height in
// buckets of half the smallest radius), so each user keeps the one its figures were measured with.

#include <algorithm>
#include <cmath>
#include <vector>

#include "mass_aggregate_sim/engine/world/world.h"

namespace mass_aggregate_sim {
namespace engine {
namespace rope {

constexpr Real kLength = 1.0;
constexpr Real kMass = 1.0;

inline Real segment(const int knots) { return kLength / static_cast<Real>(knots); }

// The knots from the anchor out. Every link went in when world.links() holds `knots` more.
inline std::vector<ParticleId> add(World& world, const int knots, const bool cables,
                                   const Real radius, const Vec3& direction = Vec3::UnitX()) {
  const Real length = segment(knots);
  std::vector<ParticleId> ids;
  for (int i = 0; i < knots; ++i) {
    ParticleSpec spec;
    spec.position = (length * static_cast<Real>(i + 1)) * direction;
    spec.inverse_mass = static_cast<Real>(knots) / kMass;
    spec.radius = radius;
    ids.push_back(*world.addParticle(spec));
  }
  if (cables) {
    world.addLink(Cable::anchoredAt(ids[0], Vec3::Zero(), length, 0.0));
  } else {
    world.addLink(Rod::anchoredAt(ids[0], Vec3::Zero(), length));
  }
  for (std::size_t i = 1; i < ids.size(); ++i) {
    if (cables) {
      world.addLink(Cable::between(ids[i - 1], ids[i], length, 0.0));
    } else {
      world.addLink(Rod::between(ids[i - 1], ids[i], length));
    }
  }
  return ids;
}

// A rope of `rods` rods (1 m, 1 kg) tied between anchors at the origin and at `span` (< 1 m) along
// x, laid as a V of its exact lengths: down along `down` at the angle acos(span) to its middle,
// then up (`rods` even). With `straight`, laid from anchor to anchor instead, its rods span / rods
// long, short of their lengths. Returns the knots from the origin out.
inline std::vector<ParticleId> tie(World& world, const int rods, const Real span, const Vec3& down,
                                   const Real radius, const bool straight = false) {
  const Real length = segment(rods);
  const Real drop = straight ? 0.0 : std::sqrt(1.0 - span * span);
  std::vector<ParticleId> ids;
  for (int i = 1; i < rods; ++i) {
    ParticleSpec spec;
    spec.position = length * (static_cast<Real>(i) * span * Vec3::UnitX() +
                              static_cast<Real>(std::min(i, rods - i)) * drop * down);
    spec.inverse_mass = static_cast<Real>(rods) / kMass;
    spec.radius = radius;
    ids.push_back(*world.addParticle(spec));
  }
  world.addLink(Rod::anchoredAt(ids.front(), Vec3::Zero(), length));
  for (std::size_t i = 1; i < ids.size(); ++i)
    world.addLink(Rod::between(ids[i - 1], ids[i], length));
  world.addLink(Rod::anchoredAt(ids.back(), span * Vec3::UnitX(), length));
  return ids;
}

}  // namespace rope
}  // namespace engine
}  // namespace mass_aggregate_sim
