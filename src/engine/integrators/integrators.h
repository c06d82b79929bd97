#pragma once
// The integrators, one policy per file: each advances the particles' velocities and positions by
// one substep (ctx.h), asking the force stage (ctx.accelerations) for the forces as often as it
// needs them. Particle damping, as the ODE term v' = ln(d) v, is part of each update:
// * explicit and semi-implicit Euler take the seeds' update and scale the new velocity by d^h: a
//   Lie splitting, first order like the methods themselves, exact for the decay alone and stable
//   for every d in [0, 1];
// * implicit Euler solves it backward with the other forces (the damping force m ln(d) v in its
//   linear system);
// * velocity and position Verlet solve the damping exactly inside each half kick (a Strang
//   splitting: second order), and RK4 integrates it with its integrating factor (Lawson's form:
//   fourth order); without damping all three are the textbook methods.
// External forces (addForce) act as constant forces over the step.

#include <cstddef>

#include "engine/world/step_caches.h"
#include "mass_aggregate_sim/engine/core/particle_store.h"
#include "mass_aggregate_sim/engine/integrators/integrator.h"

namespace mass_aggregate_sim {
namespace engine {

class StepContext;

// One substep of ctx.config.integrator, then the particles held by stiff springs moved in closed
// form (their integrated motion is replaced): velocities and, predicted from them, positions,
// which the solver stages then correct.
void integrateVelocities(StepContext& ctx);
// One substep of ctx.config.integrator.
void integrate(StepContext& ctx);

void integrateExplicitEuler(StepContext& ctx);
void integrateSemiImplicitEuler(StepContext& ctx);
void integratePositionVerlet(StepContext& ctx);
void integrateVelocityVerlet(StepContext& ctx);
void integrateRk4(StepContext& ctx);
void integrateImplicitEuler(StepContext& ctx);

// Position Verlet's history of particle i from its position and velocity, the velocity holding
// the half kick of the acceleration `behind`: v = d^(h/2) v_half + phi(h/2) a_behind and
// x_prev = x - h v_half (undamped: the Taylor start x_prev = x - v h + a h^2 / 2).
void seedVerletHistory(ParticleStore& particles, const DampingFactors& damping, std::size_t i,
                       Real h, const Vec3& behind);
// Whether the particles keep position Verlet histories of this substep, which a velocity a solver
// changed must reseed (else the next substep moves with the velocity before the change).
bool keepsVerletHistory(const StepContext& ctx);
// Particle i's history reseeded from the velocity a solver left, which holds the half kick of the
// substep's acceleration.
void reseedVerletHistory(StepContext& ctx, std::size_t i);

// beta of the position update x' = x + v h + beta a h^2 for a constant acceleration a: how much
// of a substep's velocity change the integrator's positions already followed (1 for semi-implicit
// and implicit Euler, 1/2 for the Verlets and RK4, 0 for explicit Euler).
Real positionWeight(Integrator integrator);

}  // namespace engine
}  // namespace mass_aggregate_sim
