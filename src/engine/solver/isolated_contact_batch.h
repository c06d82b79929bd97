#pragma once
// Isolated collider contacts (a ball resting on the ground: one contact with a collider, its
// particle in no other constraint) solved four at a time in vector lanes by the one contact
// response (contact_response.h), so each contact gets the bits ContactResolver's scalar instance
// gives.

#include <cstddef>
#include <cstdint>

#include "engine/solver/contact.h"
#include "mass_aggregate_sim/engine/collision/plane.h"
#include "mass_aggregate_sim/engine/core/types.h"

namespace mass_aggregate_sim {
namespace engine {

struct IsolatedBatchInputs {
  const Contact* contacts = nullptr;
  const std::uint32_t* contact_index = nullptr;  // per entry: its contact (no b)
  const Real* previous_impulse = nullptr;        // per entry: its warm start (0 when none)
  const Real* previous_friction = nullptr;  // per entry, xyz at 3e: its friction's (zero when none)
  std::size_t count = 0;                    // entries, a multiple of 4
  const Real* inverse_mass = nullptr;
  const Real* acceleration = nullptr;  // xyz of particle i at i * acceleration_stride
  std::ptrdiff_t acceleration_stride = 3;
  Real h = 0.0;
  Real slop = 0.0;
  Real follow_scale = 0.0;  // beta h
  Real inverse_follow_scale = 0.0;
};

struct IsolatedBatchOutputs {
  Real* next_warm_normal = nullptr;  // by contact index: the impulse kept for the next substep
  // By contact index, xyz at 3k: the friction impulse kept, written for a contact with friction
  // that pushed (may be null when no entry has friction).
  Real* next_warm_friction = nullptr;
  bool rubbed = false;               // an active contact had friction
  std::uint32_t* touched = nullptr;  // the particles written, in entry order (room for count)
  std::size_t touched_count = 0;
  // Running over all calls, as ContactResolver keeps them for its isolated contacts.
  Real max_penetration = 0.0;
  Real max_closing = 0.0;
  bool corrected = false;
};

// Solves the entries' contacts: velocities and positions of their particles in x and v (xyz of
// particle i at 3i), warm starts, touched particles and stats in `out`.
void solveIsolatedBatch(const IsolatedBatchInputs& in, Real* x, Real* v, IsolatedBatchOutputs& out);

// A plane collider as the collider groups test it in lanes (PlaneCollider's depth formula).
struct BatchPlane {
  PlaneCollider plane;
  Real restitution;
  Real friction;
};

// One collider contact of a particle, made by a collider kind the lanes do not test.
struct GroupContact {
  ShapeContact shape;
  Real restitution = 0.0;
  Real friction = 0.0;
  std::uint32_t collider = 0;  // its id
};

// The contacts of particle i with the colliders the lanes do not test: 0, 1 (in `contact`), or
// 2 when there are two or more, or when a swept test stopped it (those go the general way).
using OtherColliderContacts = int (*)(const void* context, std::size_t i, GroupContact& contact);

struct ColliderGroupInputs {
  const BatchPlane* planes = nullptr;
  std::size_t plane_count = 0;
  OtherColliderContacts others = nullptr;  // null: planes are all the colliders
  const void* others_context = nullptr;
  std::size_t begin = 0;  // particles [begin, end), four at a time
  std::size_t end = 0;
  const std::uint32_t* slots = nullptr;  // per particle: its id's slot, for the contact keys
  const Real* radius = nullptr;
  const Real* inverse_mass = nullptr;
  const Real* acceleration = nullptr;  // xyz of particle i at 3i
  Real margin = 0.0;                   // contacts for gaps narrower than this
  Real h = 0.0;
  Real slop = 0.0;
  Real follow_scale = 0.0;
  Real inverse_follow_scale = 0.0;
  // The last substep's warm starts, in its contact order (friction: xyz at 3k, or null).
  const std::uint64_t* warm_key = nullptr;
  const Real* warm_normal = nullptr;
  const Real* warm_friction = nullptr;
  std::size_t warm_size = 0;
};

struct ColliderGroupOutputs {
  std::size_t cursor = 0;                  // in and out: where the next warm start is looked for
  std::uint64_t* next_warm_key = nullptr;  // the contacts made, in order (room for end - begin)
  Real* next_warm_normal = nullptr;
  Real* next_warm_friction = nullptr;  // xyz at 3k; null when no collider has friction
  std::size_t contacts = 0;
  std::uint32_t* touched = nullptr;  // the particles written (room for end - begin)
  std::size_t touched_count = 0;
  Real max_penetration = 0.0;  // running, as in IsolatedBatchOutputs
  Real max_closing = 0.0;
  bool corrected = false;
  bool rubbed = false;      // an active contact had friction
  std::size_t stopped = 0;  // the first particle not handled
};

// Makes and solves the collider contacts of particles [begin, end), four consecutive particles at
// a time, while each of the four meets at most one collider (of any kind: planes are tested in
// lanes, the others by `others`) and finds its warm start at the cursor: the contacts
// generateColliderContacts() would make, solved as the isolated contacts they are, without
// writing a Contact. Returns where it stopped (a group that does not qualify, or fewer than four
// left); the caller makes those contacts the general way.
std::size_t solveColliderGroups(const ColliderGroupInputs& in, Real* x, Real* v,
                                ColliderGroupOutputs& out);

}  // namespace engine
}  // namespace mass_aggregate_sim
