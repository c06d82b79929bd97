#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "engine/collision/broadphase.h"
#include "engine/solver/contact.h"
#include "engine/solver/contact_resolver.h"
#include "mass_aggregate_sim/engine/collision/colliders.h"
#include "mass_aggregate_sim/engine/core/types.h"

namespace mass_aggregate_sim {
namespace engine {

// The contact phase's state between substeps: the impulses each contact and link ended the last
// substep with (warm starts, hashed with the world's state), the candidate pairs (whose order the
// contacts follow), and the buffers it reuses.
struct ContactWorkspace {
  std::vector<Contact> contacts;
  std::size_t position_only_contacts = 0;  // of contacts (Contact::position_only)
  // generateColliderContacts() also makes position-only contacts (pairs or links present).
  bool collider_position_only = false;
  std::vector<BatchPlane> batch_planes;  // the planes, tested in the collider groups' lanes
  // This substep's generation gave some particle contacts with two or more colliders.
  bool particle_in_two_collider_contacts = false;
  std::vector<LinkGeometry> links;  // of the link contacts, by Contact::link
  // A particle's contact with the surface of a body, as the body contact stage found it in the
  // first substep, as a plane along the contact's normal, each substep at the particle's position
  // then. A still body's (fixed or asleep) is the particle solver's as a collider's: a pile
  // resting in a still bin is the particles' own pile, solved as on colliders, and no body row
  // joins it. A moving body's is the body rows' and only keeps the particle out in the positions
  // stage (position-only), the plane following the body (findBodyPairs).
  struct BodySurface {
    std::uint32_t particle = 0;
    std::uint32_t shape = 0;
    Vec3 normal = Vec3::UnitZ();
    Real offset = 0.0;  // separation = n.x - offset (the radii in it)
    Material material;  // combined as the body contact's
    bool moves = false;
  };
  std::vector<BodySurface> body_surfaces;  // this step's (made when the world has bodies)
  std::vector<std::uint32_t> slots;        // per particle: its id's slot, for the contact keys
  std::uint64_t slots_layout = ~std::uint64_t{0};  // ParticleStore::layoutVersion() of slots
  std::vector<Contact> sorted_contacts;
  // Bottom-up order: per pair or contact its height bucket, and the counting sort's buckets.
  std::vector<std::uint32_t> particle_bucket;
  std::uint32_t buckets = 0;  // this substep's bucket count; 0 until particle_bucket is made
  std::vector<std::uint32_t> item_bucket;
  std::vector<std::uint32_t> bucket_start;
  // Candidate pairs, kept between substeps while valid: the pairs less than candidate_skin beyond
  // reach (and margin), they hold while no particle moved more than half of it from
  // candidate_positions and nothing else they depend on changed (particle layout and radii,
  // broadphase, slop, gravity).
  std::vector<IndexPair> pairs;
  bool candidates_valid = false;
  Real candidate_skin = 0.0;
  Vec3Array candidate_positions;
  ScalarArray candidate_radii;
  std::uint64_t candidate_layout = 0;
  Broadphase candidate_broadphase = Broadphase::kSortAndSweep;
  Real candidate_slop = 0.0;
  Vec3 candidate_gravity = Vec3::Zero();
  std::vector<IndexPair> sorted_pairs;
  std::vector<std::uint8_t> pair_is_swept;  // per pair: caught by the swept test this substep
  std::vector<std::uint64_t> linked_pairs;  // sorted (min dense << 32 | max dense) of linked pairs
  Vec3Array box_lo;
  Vec3Array box_hi;
  Vec3Array substep_start;           // positions before integration, kept only when CCD is on
  std::vector<Real> time_of_impact;  // per particle, fraction of the substep; 1 = none
  // Per particle: the collider its swept test hit first (index into ccd_hits), or -1.
  std::vector<std::int32_t> collider_hit;
  struct ColliderHit {
    ColliderId collider;
    Real time;
    Vec3 normal;
    Real restitution;
    Real friction;
  };
  std::vector<ColliderHit> collider_hits;
  // Swept results exist only when the swept tests ran this substep (n particles).
  bool sweptThisSubstep(const bool continuous, const std::size_t n) const {
    return continuous && time_of_impact.size() == n && collider_hit.size() == n &&
           pair_is_swept.size() == pairs.size();
  }
  // This substep's contacts were made and solved in parts (ContactResolver::addPart).
  bool solved_in_parts = false;
  BroadphaseFinder broadphase;
  ContactResolver resolver;
};

}  // namespace engine
}  // namespace mass_aggregate_sim
