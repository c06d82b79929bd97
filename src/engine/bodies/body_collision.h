#pragma once
// Which body shapes touch what, once per step: the broadphase (a dynamic tree of fattened boxes
// of the body shapes and the static colliders other than planes), then the narrowphase of each
// candidate pair (shape-shape, shape-collider, shape-particle), kept as contacts in key order
// with the impulses their points carried from the last step.

#include <cstdint>
#include <vector>

#include "engine/bodies/body_workspace.h"
#include "mass_aggregate_sim/engine/bodies/body_settings.h"
#include "mass_aggregate_sim/engine/bodies/body_store.h"
#include "mass_aggregate_sim/engine/collision/colliders.h"
#include "mass_aggregate_sim/engine/collision/collision_settings.h"
#include "mass_aggregate_sim/engine/collision/particle_materials.h"
#include "mass_aggregate_sim/engine/core/particle_store.h"
#include "mass_aggregate_sim/engine/joints/joints.h"

namespace mass_aggregate_sim {
namespace engine {

struct BodyCollisionScene {
  const BodyStore& bodies;
  const Colliders& colliders;
  std::uint64_t colliders_version;
  const ParticleStore& particles;
  const CollisionSettings& collisions;
  const ParticleMaterials& materials;
  const BodySettings& settings;
  // A joint whose collide_connected is false keeps its two ends (bodies, or a body and a
  // particle) from touching: their contacts would fight it.
  const Joints& joints;
  Real dt;
  // The particles' positions are the integrator's prediction for the substep, this times their
  // velocity ahead of where they move from (beta h, storeParticles): they are met from there.
  Real particle_lead;
};

// Puts every shape in the tree (new ones), moves the awake bodies' shapes, and remakes the
// colliders' proxies when they changed.
void updateBodyProxies(const BodyCollisionScene& scene, BodyStore& bodies, BodyWorkspace& ws);
// Removes a body's shapes from the tree (before the store forgets them).
void removeBodyProxies(BodyStore& bodies, std::size_t dense, BodyWorkspace& ws);
// The step's contacts into ws.contacts (sorted), each point's impulses carried over by key and
// feature id. Contacts where no side is awake are kept as they were; the others are listed in
// ws.awake_contacts. Two ends of a joint that does not collide_connected never touch.
void findBodyContacts(const BodyCollisionScene& scene, BodyWorkspace& ws);
// The dense indices of the bodies with a shape whose stored (fat) box overlaps box, as the tree
// holds them; a body may come more than once.
std::vector<std::size_t> bodiesNear(const BodyStore& bodies, const BodyWorkspace& ws,
                                    const Aabb& box);
// ws.awake_contacts: the contacts with an awake side or a particle, as the bodies are now.
void listAwakeContacts(const BodyStore& bodies, BodyWorkspace& ws);
// Mean restitution and geometric-mean friction: the particles' rule, for every pair.
Material combineMaterials(const Material& a, const Material& b);

}  // namespace engine
}  // namespace mass_aggregate_sim
