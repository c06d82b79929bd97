#pragma once

#include "mass_aggregate_sim/engine/core/types.h"

namespace mass_aggregate_sim {
namespace engine {

// What the integrators carry from one substep to the next: part of the world's state (copied with
// it, and what a copy steps on from).
struct IntegratorState {
  // Position Verlet: the particles' histories (ParticleStore::previousPositions ...) were seeded
  // for this substep length (another h seeds them all again); some particle's must be seeded; the
  // last substep had external forces.
  Real verlet_history_h = 0.0;
  bool verlet_unseeded = true;
  bool external_in_history = false;
  // Velocity Verlet: the accelerations without external forces evaluated where the last substep
  // ended (at its predicted velocity), reused as the next one's start while valid.
  bool acceleration_valid = false;
  Vec3Array internal_acceleration;
  // Each particle's acceleration over the substep (the average over RK4's stages): the contact
  // phase measures what the forces built with it. The semi-implicit Euler pass writes it only
  // when the contact phase runs (StepContext::contacts_active); nothing else reads it.
  Vec3Array acceleration;
};

}  // namespace engine
}  // namespace mass_aggregate_sim
