#pragma once
// Isolated frictionless collider contacts (a ball resting on the ground: one contact with a
// collider, its particle in no other constraint) solved four at a time in vector lanes, with the
// arithmetic of ContactResolver::solveIsolated<false> in the same order, so each contact gets the
// bits the scalar code gives.

#include <cstddef>
#include <cstdint>

#include "mass_aggregate_sim/engine/contact.h"
#include "mass_aggregate_sim/engine/types.h"

namespace mass_aggregate_sim {
namespace engine {

struct IsolatedBatchInputs {
  const Contact* contacts = nullptr;
  const std::uint32_t* contact_index = nullptr;  // per entry: its contact (no b, no friction)
  const Real* previous_impulse = nullptr;        // per entry: its warm start (0 when none)
  std::size_t count = 0;                         // entries, a multiple of 4
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

}  // namespace engine
}  // namespace mass_aggregate_sim
