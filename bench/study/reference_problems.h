#pragma once

#include <functional>
#include <string>
#include <vector>

#include "mass_aggregate_sim/engine/world/world.h"

namespace mass_aggregate_sim {
namespace study {

using engine::Integrator;
using engine::Real;
using engine::Vec3;
using engine::Vec3Array;
using engine::World;

// A reference problem of the accuracy study: a scene, how long to run it, and the positions it
// must end at (from a closed form, or from a run of RK4 at a tiny step).
struct ReferenceProblem {
  std::string name;
  std::string description;
  Real duration = 0.0;
  std::function<World(Integrator integrator, Real dt)> build;
  // Exact final positions, or empty to use a reference run.
  std::function<Vec3Array()> exact;
};

// Undamped harmonic oscillator: m = 1, k = 1 (omega = 1), x0 = 1, v0 = 0; x(t) = cos t.
ReferenceProblem undampedOscillator();
// Damped oscillator, damping ratio 0.1 from the spring's dashpot:
// x(t) = e^(-zeta t) (cos(w_d t) + zeta / w_d sin(w_d t)), w_d = sqrt(1 - zeta^2).
ReferenceProblem dampedOscillator();
// Ten unit masses joined by springs (k = 100, rest 1), the first tied to an anchor, released
// horizontally under gravity: a swinging, stretching chain.
ReferenceProblem springChain();
// A unit mass thrown at (30, 30, 0) m/s under gravity with quadratic drag k2 = 0.05.
ReferenceProblem dragProjectile();
// The seeds' projectile with particle damping: 200 kg thrown at (40, 30, 0) m/s from 1.5 m,
// g = 20 m/s^2, damping d = 0.5 (half the velocity kept per second, so the damping shows at
// every dt), 4 s. v' = ln(d) v + g has the closed form
// x(t) = x0 + phi(t) v0 + (phi(t) - t) / ln(d) g, phi(t) = (d^t - 1) / ln(d).
ReferenceProblem dampedProjectile();

// Runs the scene to the problem's duration; returns the final positions.
Vec3Array finalPositions(const ReferenceProblem& problem, Integrator integrator, Real dt);

}  // namespace study
}  // namespace mass_aggregate_sim
