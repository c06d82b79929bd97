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
  //   E_ref + (S (1 + energy_growth_limit) - 1) (kinetic + elastic)_ref + M |g|^2 dt^2 n
  //         + 1e-9 |energies|
  // is a divergence: S = energySwing() (stability.h) of the integrator at the stiffest spring's
  // omega h, the most its reported energy swings along a bounded orbit (1 for explicit and
  // implicit Euler and RK4, which never gain energy on a stable orbit), M the movable mass, n the
  // steps since the reference (explicit Euler's truncation under gravity). So no bounded orbit
  // below the integrator's stability limit trips it (up to 0.999 of the limit, where S is capped),
  // and an exponential runaway is caught within a few steps. The state each step ends in is
  // judged in that step. Cost: one pass over the particles (kinetic and gravitational energy, and
  // the finiteness check in the same pass); the elastic energy comes from evaluating the next
  // step's forces early (semi-implicit Euler, one substep, no contacts; that step then uses them)
  // or else from one more pass over the springs. 0 turns the guard off.
  Real energy_growth_limit = 10.0;
};

// dt finite and in (0, 1], substeps in [1, 1000], gravity finite, max_frame_time finite and >= dt,
// energy_growth_limit finite and >= 0.
Status validateConfig(const WorldConfig& config);

}  // namespace engine
}  // namespace mass_aggregate_sim
