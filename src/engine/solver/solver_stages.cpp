#include "engine/solver/solver_stages.h"

#include <algorithm>

#include "engine/collision/contact_stages.h"
#include "engine/integrators/integrators.h"
#include "engine/solver/contact_workspace.h"
#include "engine/world/step_context.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

// Only collider contacts: each particle's are made together, so they are made and solved in parts
// of particles while they are still in the cache (the same results as all at once: see
// ContactResolver::beginParts). Groups of four consecutive particles that each meet at most one
// collider are made and solved in vector lanes (solveColliderGroups), planes tested in the lanes;
// the group where that stops goes the general way: its contacts written and solved as a part
// (where no particle of it meets two colliders, every contact of it is isolated without counting).
void solveColliderContactsInParts(StepContext& ctx) {
  constexpr std::size_t kPartParticles = 256;
  ContactWorkspace& ws = ctx.contacts;
  ParticleStore& particles = ctx.particles;
  const std::size_t n = particles.size();
  const CollisionSettings& settings = ctx.collisions;
  const Real h = ctx.h;
  const Vec3Array& acceleration = ctx.integration.acceleration;
  const Real margin = contactMargin(settings.penetration_slop);
  const auto& planes = ctx.colliders.of<PlaneCollider>();
  ws.batch_planes.clear();
  for (const PlaneCollider& c : planes) {
    ws.batch_planes.push_back(BatchPlane{c, c.material.restitution, c.material.friction});
  }
  bool any_friction = false;
  ctx.colliders.forEach([&](const auto& shapes) {
    for (const auto& shape : shapes) any_friction = any_friction || shape.material.friction > 0.0;
  });
  ColliderGroupInputs groups;
  groups.planes = ws.batch_planes.data();
  groups.plane_count = ws.batch_planes.size();
  if (ctx.colliders.size() != planes.size() || ws.sweptThisSubstep(settings.continuous, n)) {
    groups.others = &otherColliderContacts;
    groups.others_context = &ctx;
  }
  groups.slots = ws.slots.data();
  groups.radius = particles.radii().data();
  groups.margin = margin;
  groups.h = h;
  groups.slop = settings.penetration_slop;
  ws.collider_position_only = false;  // nothing but its own collider contacts moves a particle
  ws.resolver.beginParts(static_cast<Eigen::Index>(n), h, positionWeight(ctx.config.integrator));
  for (std::size_t begin = 0; begin < n && !ctx.colliders.empty(); begin += kPartParticles) {
    const std::size_t end = std::min(n, begin + kPartParticles);
    std::size_t i = begin;
    while (i < end) {
      groups.begin = i;
      groups.end = end;
      i = ws.resolver.addColliderGroups(groups, any_friction, particles.positions(),
                                        particles.velocities(), particles.inverseMasses(),
                                        acceleration);
      if (i >= end) break;
      // The group the lanes stopped at (or the last particles of the part): the general way.
      const std::size_t stop = std::min(end, i + 4);
      ws.contacts.clear();
      const bool in_two = generateColliderContacts(ctx, i, stop);
      ws.resolver.addPart(ws.contacts, particles.positions(), particles.velocities(),
                          particles.inverseMasses(), acceleration, h, settings.penetration_slop,
                          in_two ? IsolatedContacts::kFind : IsolatedContacts::kAll);
      i = stop;
    }
  }
  ws.resolver.finishPartsVelocities(particles.positions(), particles.velocities(),
                                    particles.inverseMasses(), acceleration, settings,
                                    ctx.contact_stats);
  ws.contacts.clear();
  ws.solved_in_parts = true;
}

}  // namespace

void solveConstraints(StepContext& ctx) {
  if (!ctx.contacts_active) return;
  ContactWorkspace& ws = ctx.contacts;
  const CollisionSettings& settings = ctx.collisions;
  ParticleStore& particles = ctx.particles;
  ws.solved_in_parts = false;
  const bool only_colliders = onlyColliderContacts(ctx);
  const bool surfaces = ctx.bodies && !ws.body_surfaces.empty();
  if (only_colliders && settings.max_contacts == 0) {
    if (!surfaces) {
      solveColliderContactsInParts(ctx);
      return;
    }
    // The contact stage left the collider contacts to the parts; with still bodies' surfaces
    // they are made here, all at once, beside those.
    ws.collider_position_only = false;
    ws.particle_in_two_collider_contacts =
        !ctx.colliders.empty() && generateColliderContacts(ctx, 0, particles.size());
    addBodySurfaceContacts(ctx);
  }
  // Isolated contacts are looked for when all contacts are with colliders (most are then
  // isolated: a particle meets two colliders only in a corner); with particle pairs or links
  // few are, and the count would cost more than it saves.
  IsolatedContacts isolated = IsolatedContacts::kNone;
  if (only_colliders) {
    isolated = ws.particle_in_two_collider_contacts || surfaces ? IsolatedContacts::kFind
                                                                : IsolatedContacts::kAll;
  }
  ws.resolver.solveVelocities(ws.contacts, ws.links, particles.positions(), particles.velocities(),
                              particles.inverseMasses(), ctx.integration.acceleration, ctx.h,
                              settings, positionWeight(ctx.config.integrator), ctx.contact_stats,
                              isolated, particles.radii().data());
}

void integratePositions(StepContext& ctx) {
  if (!ctx.contacts_active) return;
  ContactWorkspace& ws = ctx.contacts;
  ParticleStore& particles = ctx.particles;
  const Real h = ctx.h;
  const std::vector<Contact>& contacts =
      ws.solved_in_parts ? ws.resolver.noContacts() : ws.contacts;
  ws.resolver.correctPositions(contacts, particles.positions(), particles.velocities(),
                               particles.inverseMasses(), h, ctx.collisions, ctx.contact_stats);
  ctx.contact_stats.contacts = ws.solved_in_parts ? ws.resolver.partsContactCount()
                                                  : ws.contacts.size() - ws.position_only_contacts;
  ctx.contact_stats.dropped = ctx.dropped;

  const auto& touched = ws.resolver.touched();
  if (touched.empty() && ctx.contact_stats.ccd_hits == 0) return;
  // The integrators' histories follow what the solver changed.
  IntegratorState& integration = ctx.integration;
  integration.acceleration_valid = false;
  if (keepsVerletHistory(ctx)) {
    for (const std::uint32_t i : touched) reseedVerletHistory(ctx, i);
    if (ws.sweptThisSubstep(ctx.collisions.continuous, particles.size())) {
      for (std::size_t i = 0; i < particles.size(); ++i) {
        if (ws.time_of_impact[i] < 1.0) reseedVerletHistory(ctx, i);
      }
    }
  }
}

}  // namespace engine
}  // namespace mass_aggregate_sim
