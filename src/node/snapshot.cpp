#include "mass_aggregate_sim/node/snapshot.h"

#include <algorithm>
#include <type_traits>

namespace mass_aggregate_sim {
namespace node {
namespace {

using engine::Real;
using engine::Vec3;

void takeLinks(const engine::World& world, std::vector<LinkSegment>& out) {
  out.clear();
  const engine::ParticleStore& particles = world.particles();
  const engine::ForceGenerators& g = world.generators();
  const auto x = particles.positions();
  const auto at = [&](const engine::ParticleId id) -> Vec3 {
    return x.col(particles.denseIndexUnchecked(id));
  };
  const auto segment = [&](const Vec3& a, const Vec3& b, const Real tension) {
    out.push_back(LinkSegment{a, b, tension});
  };
  g.forEach([&](const auto& kind) {
    using Kind = typename std::decay_t<decltype(kind)>::value_type;
    if constexpr (engine::ForceKind<Kind>::kDrawn) {
      for (const Kind& generator : kind) {
        const engine::DrawnSegment drawn = engine::ForceKind<Kind>::drawn(generator, particles);
        segment(drawn.a, drawn.b, drawn.tension);
      }
    }
  });
  for (const engine::PointSpring& spring : world.bodyGenerators().of<engine::PointSpring>()) {
    const engine::DrawnSegment drawn =
        engine::BodyForceKind<engine::PointSpring>::drawn(spring, world.bodies(), particles);
    segment(drawn.a, drawn.b, drawn.tension);
  }
  const engine::Links& links = world.links();
  if (links.empty()) return;
  // World::linkTensions is sorted by id.
  const std::vector<engine::LinkTension> tensions = world.linkTensions();
  const auto tension = [&](const engine::GeneratorId id) -> Real {
    const auto it = std::lower_bound(
        tensions.begin(), tensions.end(), id,
        [](const engine::LinkTension& t, const engine::GeneratorId key) { return t.id < key; });
    return it != tensions.end() && it->id == id ? it->tension : 0.0;
  };
  links.forEach([&](const auto& kind) {
    for (const auto& link : kind) {
      segment(at(link.a), link.anchored() ? link.anchor : at(link.b), tension(link.id));
    }
  });
}

}  // namespace

void takeSnapshot(const engine::World& world, WorldSnapshot& out, const JointNames& joint_names,
                  const bool contacts) {
  const engine::ParticleStore& particles = world.particles();
  const std::size_t n = particles.size();
  out.step = world.stepCount();
  out.time = world.time();
  out.positions = particles.positions();
  out.velocities = particles.velocities();
  out.inverse_masses = particles.inverseMasses();
  out.radii = particles.radii();
  out.ids.resize(n);
  out.names.resize(n);
  out.named = 0;
  for (std::size_t i = 0; i < n; ++i) {
    out.ids[i] = particles.idAt(i).packed();
    // Assignment keeps the string's buffer: no allocation once the names are known.
    if (out.names[i] != particles.name(i)) out.names[i] = particles.name(i);
    if (!out.names[i].empty()) ++out.named;
  }
  takeLinks(world, out.links);
  takeBodySnapshot(world, joint_names, contacts, out.bodies);
}

}  // namespace node
}  // namespace mass_aggregate_sim
