#pragma once

#include <limits>
#include <string>

#include "mass_aggregate_sim/engine/force_generators.h"
#include "mass_aggregate_sim/engine/integrator.h"
#include "mass_aggregate_sim/engine/particle_store.h"
#include "mass_aggregate_sim/engine/types.h"

namespace mass_aggregate_sim {
namespace engine {

// What World does after it detects a divergence (a non-finite position or velocity, or energy
// growing beyond the bound of WorldConfig::energy_growth_limit in a step without external work).
// In every case the event is recorded (World::lastDivergence, divergenceCount) first.
enum class DivergencePolicy {
  kContinue,  // keep stepping: the caller decides what to do with the report
  kPause,     // step() and advance() do nothing until World::resume()
  kReset,     // restore the snapshot taken by World::setResetSnapshot() (time, state, config);
              // without a snapshot it pauses instead
};

const char* divergencePolicyName(DivergencePolicy policy);

// Largest omega*h at which the integrator keeps the undamped oscillator x'' = -omega^2 x bounded
// (strictly below it the amplitude stays bounded):
//   explicit Euler 0 (each step multiplies the amplitude by sqrt(1 + (omega h)^2) > 1),
//   semi-implicit Euler, position and velocity Verlet 2, RK4 2 sqrt(2), implicit Euler infinity.
Real stabilityLimit(Integrator integrator);

// The limit on omega*h with particle damping: v is multiplied by d^h each step. Only explicit
// Euler changes: the amplitude factor per step is sqrt(d^h (1 + (omega h)^2)), at most 1 while
// omega h <= sqrt(d^-h - 1). The others keep their undamped limit (damping only widens it).
Real stabilityLimit(Integrator integrator, Real damping, Real h);

// The largest substep h that keeps a mode of angular frequency omega stable (infinity when any h
// does, 0 when none does).
Real largestStableSubstep(Integrator integrator, Real omega, Real damping);

// The stiffest spring of a scene against the integrator's limit. Springs and bungees between two
// particles and anchored ones count; stiff springs (solved in closed form) never limit the step.
// omega = sqrt(k/mu) with mu the reduced mass m_a m_b / (m_a + m_b) (anchored, or the other end
// immovable: the particle's mass). A spring shares particles with others, so the fastest mode it
// takes part in can be faster: coupled_omega is the Gershgorin bound on that mode from the
// edge form of the stiffness matrix, omega_e^2 <= sqrt(k_e) (s_a / m_a + s_b / m_b) with s_i the
// sum of sqrt(k) over the springs at particle i. It equals omega for an isolated spring and the
// exact highest frequency 2 sqrt(k/m) inside a uniform chain; the guard uses it.
struct StabilityReport {
  bool stable = true;
  GeneratorId generator = 0;  // the spring closest to (or furthest beyond) its limit; 0: none
  Real omega = 0.0;           // that spring's sqrt(k/mu), rad/s
  Real coupled_omega = 0.0;   // the bound on the fastest mode it takes part in, rad/s
  Real omega_h = 0.0;         // coupled_omega * substep length
  Real limit = std::numeric_limits<Real>::infinity();  // the integrator's limit on omega*h
  // The largest step dt that is stable with substeps_used substeps (a strict bound: any dt
  // below it is stable); infinity when every dt is, 0 when none is.
  Real stable_dt = std::numeric_limits<Real>::infinity();
  // The substeps the world steps with: config().substeps, or substeps_needed when auto_substep
  // raises them (`stable` still describes config().substeps, so the warning stays visible).
  int substeps_used = 1;
  int substeps_needed = 1;  // the fewest substeps that make dt stable; 0 when none up to 1000 do
  std::string message;      // empty when stable
};

// Analyses the scene for a step dt split into substeps.
StabilityReport analyseStability(const ForceGenerators& generators, const ParticleStore& particles,
                                 Integrator integrator, Real dt, int substeps);

}  // namespace engine
}  // namespace mass_aggregate_sim
