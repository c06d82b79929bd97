#pragma once

#include <limits>
#include <string>

#include "mass_aggregate_sim/engine/bodies/body_store.h"
#include "mass_aggregate_sim/engine/core/particle_store.h"
#include "mass_aggregate_sim/engine/core/types.h"
#include "mass_aggregate_sim/engine/forces/body_force_generators.h"
#include "mass_aggregate_sim/engine/forces/force_generators.h"
#include "mass_aggregate_sim/engine/integrators/integrator.h"

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

// The largest substep h that keeps a mode of angular frequency omega at omega*h < fraction times
// the limit (1: stable; infinity when any h does, 0 when none does).
Real largestStableSubstep(Integrator integrator, Real omega, Real damping, Real fraction = 1.0);

// The same for a damped mode x'' = -omega^2 x - gamma x' (a spring with damping c on its line:
// gamma = c / mu), which the integrators take explicitly: each step's map of (x, v) is linear,
// and it stays bounded while (Jury's conditions on its trace and determinant)
//   semi-implicit Euler      (omega h)^2 + 2 gamma h <= 4
//   position, velocity Verlet (omega h)^2 + 4 gamma h <= 4 (their damping reads the velocity of
//                            the step before)
//   RK4                      |R(h lambda)| <= 1 at both roots of lambda^2 + gamma lambda + omega^2,
//                            R(z) = 1 + z + z^2/2 + z^3/6 + z^4/24 (found by bisection)
//   implicit Euler           any h (it solves with the damping's df/dv)
//   explicit Euler           as without gamma (damping can only widen its range; not credited).
// A critically damped spring (gamma = 2 omega) is stable under semi-implicit Euler only while
// omega h <= 2 sqrt(2) - 2 = 0.83, not 2. gamma = 0 gives largestStableSubstep exactly.
Real largestStableDampedSubstep(Integrator integrator, Real omega, Real gamma, Real damping,
                                Real fraction = 1.0);

// auto_substep keeps omega*h at or below this fraction of the integrator's limit: at the limit
// itself an orbit is barely bounded and its energy swings without bound (energySwing).
constexpr Real kAutoSubstepMargin = 0.9;

// The largest factor by which the energy an integrator reports along a bounded orbit of the
// undamped oscillator x'' = -omega^2 x can exceed the energy it reported at any earlier point of
// the same orbit, for omega*h below its stability limit (infinity at or above). One step maps the
// state linearly and keeps a quadratic form G; the orbit stays on a level set of G, so the swing is
// the ratio of the extreme values of the reported energy Q on that set, lambda_max / lambda_min
// of Q against G (docs/ACCURACY.md derives each). Explicit Euler, which has no bounded undamped
// orbit, has swing 1 at every omega*h: any rise of its energy is growth.
//   semi-implicit Euler (1 + omega h / 2) / (1 - omega h / 2);
//   velocity Verlet 1 / (1 - (omega h / 2)^2);
//   position Verlet, whose velocity is (x' - x) / h + a h / 2: (B + r) / (B - r) with
//     B = 2 + 3 (omega h)^2 / 4 and r = (omega h)^2 / 4 sqrt(9 + 4 (omega h)^2);
//   RK4 and implicit Euler 1: below their limits each step maps the energy norm to at most
//     itself.
Real energySwing(Integrator integrator, Real omega_h);
// The swing the energy guard allows for a stiffest mode at omega_h: energySwing at omega_h, taken
// at most at 0.999 of the limit, so a mode at or beyond the limit, which runs away, is still
// caught.
Real guardSwing(Integrator integrator, Real omega_h);

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
  // The integrator's limit on omega*h; for a damped spring, omega times the largest stable
  // substep (largestStableDampedSubstep).
  Real limit = std::numeric_limits<Real>::infinity();
  Real damping_rate = 0.0;  // that spring's damping c / mu (the coupled bound), 1/s
  // The largest step dt that is stable with substeps_used substeps (a strict bound: any dt
  // below it is stable); infinity when every dt is, 0 when none is.
  Real stable_dt = std::numeric_limits<Real>::infinity();
  // The substeps the world steps with: config().substeps, or substeps_with_margin when
  // auto_substep raises them (`stable` still describes config().substeps, so the warning stays
  // visible).
  int substeps_used = 1;
  int substeps_needed = 1;  // the fewest substeps that make dt stable; 0 when none up to 1000 do
  // The fewest substeps that keep omega*h at or below kAutoSubstepMargin of the limit (what
  // auto_substep takes); 0 when none up to 1000 do.
  int substeps_with_margin = 1;
  std::string message;  // empty when stable
};

// Analyses the scene for a step dt split into substeps; with_damping takes each spring's damping
// into its limit (largestStableDampedSubstep), else every spring counts as undamped (the ranking
// the energy guard reads: its swing is the stiffest undamped mode's).
StabilityReport analyseStability(const ForceGenerators& generators, const ParticleStore& particles,
                                 Integrator integrator, Real dt, int substeps,
                                 bool with_damping = true);

// The same for the springs on bodies (PointSpring), each alone (no coupled bound), with
// omega = sqrt(k (g_a + g_b)) and g an end's largest 1/m_eff along any line (1/m + |r|^2 / I_min
// at a point r from a body's centre of mass: a bound whatever the body's turn). A body end moves
// under semi-implicit Euler (limit 2), a particle end under the particles' integrator; the
// tighter limit of the two ends holds. substeps: those the bodies step with.
StabilityReport analysePointSpringStability(const BodyForceGenerators& generators,
                                            const BodyStore& bodies, const ParticleStore& particles,
                                            Integrator particle_integrator, Real dt, int substeps);

// Largest rate*h at which an integrator keeps a drag's decay v' = -rate v bounded (the drag is
// taken explicitly, at the velocity it knows): explicit and semi-implicit Euler 2
// (v' = (1 - rate h) v); position and velocity Verlet 1 (their drag reads the velocity of the
// step before, v'' = v' - rate h v, whose roots have modulus sqrt(rate h)); RK4 2.7853, the real
// root of z^3 - 4 z^2 + 12 z - 24 (where its factor 1 - z + z^2/2 - z^3/6 + z^4/24 returns to 1);
// implicit Euler infinity (its solve takes the drag's df/dv). Each found to 1e-4 by running a
// dragged particle (DragStability.* in the engine tests).
Real decayLimit(Integrator integrator);

// The strongest drag of the particles (ForceKind<K>::decay: k1 / m; the k2 |v| v part's rate
// grows with the speed and is not bounded here) against the integrator's decay limit, with the
// report's omega its rate, named "drag"; and of the bodies (BodyForceKind<K>::decay: k1 / m and
// angular / I_min, "angular drag"), which semi-implicit Euler moves, at the bodies' substeps.
StabilityReport analyseDragStability(const ForceGenerators& generators,
                                     const ParticleStore& particles, Integrator integrator, Real dt,
                                     int substeps);
StabilityReport analyseBodyDragStability(const BodyForceGenerators& generators,
                                         const BodyStore& bodies, const ParticleStore& particles,
                                         Real dt, int substeps);

// The binding one of two reports on the same dt: the smaller stable dt (its spring, omega and
// message), unstable if either is, and the most substeps either needs (0, none up to 1000, wins).
StabilityReport bindingReport(const StabilityReport& a, const StabilityReport& b);

}  // namespace engine
}  // namespace mass_aggregate_sim
