#pragma once

#include "mass_aggregate_sim/engine/core/status.h"
#include "mass_aggregate_sim/engine/core/types.h"
#include "mass_aggregate_sim/engine/integrators/integrator.h"
#include "mass_aggregate_sim/engine/world/stability.h"

namespace mass_aggregate_sim {
namespace engine {

struct WorldConfig {
  Real dt = 1.0 / 60.0;  // fixed step, s
  int substeps = 1;      // each step is split into this many equal substeps
  Integrator integrator = Integrator::kSemiImplicitEuler;
  Vec3 gravity = Vec3::Zero();  // m/s^2, applied to every movable particle
  // advance(): longest frame time taken at once, so a stall does not cause a spiral of catch-up.
  Real max_frame_time = 0.25;
  // Stability guard (stability.h). With auto_substep a step whose stiffest spring would be
  // unstable at dt / substeps takes the fewest substeps (up to 1000) that make it stable.
  bool auto_substep = false;
  DivergencePolicy divergence_policy = DivergencePolicy::kContinue;
  // Energy guard, for worlds with force generators. The reference is the state at the first step
  // after the last scene change or external work (addForce, any set or add call); per-particle
  // accelerations and buoyancy do work the energy omits, so they turn the guard off. A step that
  // leaves kinetic + gravitational + elastic energy above
  //   E_ref + energy_growth_limit * (kinetic + elastic)_ref + M |g|^2 dt^2 n + 1e-9 |energies|
  // (M the movable mass, n the steps since the reference: explicit Euler's truncation under
  // gravity) is a divergence. A symplectic integrator's energy swings by up to
  // 1 / (1 - (omega h / 2)^2) along a stable orbit, so the default 10 stays silent up to
  // omega h ~ 1.9 and fires within a few steps of any exponential runaway. The state each step
  // ends in is judged in that step. Cost: one pass over the particles (kinetic and gravitational
  // energy, and the finiteness check in the same pass); the elastic energy comes from evaluating
  // the next step's forces early (semi-implicit Euler, one substep, no contacts; that step then
  // uses them) or else from one more pass over the springs. 0 turns the guard off.
  Real energy_growth_limit = 10.0;
};

// dt finite and in (0, 1], substeps in [1, 1000], gravity finite, max_frame_time finite and >= dt,
// energy_growth_limit finite and >= 0.
Status validateConfig(const WorldConfig& config);

}  // namespace engine
}  // namespace mass_aggregate_sim
