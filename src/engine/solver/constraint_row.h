#pragma once
// A constraint row: one contact, cable or rod as the velocity and position passes see it.
//
// A row acts along one direction n between side a and side b. Its Jacobian is
//   J = [ n   (r_a x n)   -n   -(r_b x n) ]
// over (v_a, w_a, v_b, w_b), r the contact point from each body's centre; the linear parts are
// n and -n, so the row stores n once. Its effective mass is
//   m = 1 / (w_a + w_b + (r_a x n).I_a^-1 (r_a x n) + (r_b x n).I_b^-1 (r_b x n)),
// its bias the target separating velocity, its bounds [0, inf) for a contact or a cable (pushes
// only, pulls only) and (-inf, inf) for a rod, and its total the accumulated impulse that warm
// starts the next substep.
//
// A particle has no orientation: no r x n, no inertia. The angular part is the Sides type: for
// particles (ParticleSides) it is empty, so a particle row stores and computes no angular term and
// is one cache line; a side kind that turns brings its own Sides (the angular Jacobians and the
// effective mass that needs them) and the passes' angular terms behind Sides::kTurns.

#include <cstdint>

#include "engine/core/body_ref.h"
#include "engine/solver/contact.h"
#include "mass_aggregate_sim/engine/core/types.h"

namespace mass_aggregate_sim {
namespace engine {

struct RowFlags {
  enum : std::uint8_t {
    kHasB = 1,         // a second body (else a collider or an anchor)
    kActive = 2,       // takes part in the velocity phase
    kResting = 4,      // resting: target 0 (or touching), follows its impulse in position
    kFriction = 8,     // a contact with friction > 0
    kUnilateral = 16,  // pushes only (contact) or pulls only (cable): total impulse >= 0
    kMovable = 32,     // w_a + w_b > 0 (else never moved, never corrected)
    kInBlock = 64,     // a link solved with the links it hangs with as one block (LinkBlocks)
    kSwept = 128,      // kActive and not kInBlock: solved row by row by the velocity sweep
  };
};

// Both sides particles: no angular part.
struct ParticleSides {
  static constexpr bool kTurns = false;
};

// Aligned to a cache line: a row the velocity pass leaves unchanged is not written back, and each
// row is one line to fetch.
template <typename Sides>
struct alignas(64) ConstraintRow : RowFlags, Sides {
  BodyRef a;
  BodyRef b;  // a when there is no second body (never moved: w_b = 0)
  std::uint8_t flags;
  ContactKind kind;
  Vec3 normal;  // the linear Jacobian of side a (side b's is -normal)
  // How far a must move along normal (relative to b): the contact's overlap (links: length
  // error). The effective mass is summed again where needed from the inverse masses (same bits).
  Real penetration;
  Real total;   // accumulated impulse this substep (starts from the warm start)
  Real target;  // the bias: the target separating velocity

  // The bounds of total: [0, inf) when unilateral, else (-inf, inf).
  bool unilateral() const { return (flags & kUnilateral) != 0; }
};

using ParticleRow = ConstraintRow<ParticleSides>;
static_assert(sizeof(ParticleRow) == 64, "a particle row is one cache line");

}  // namespace engine
}  // namespace mass_aggregate_sim
