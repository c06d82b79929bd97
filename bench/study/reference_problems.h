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

// Positions are compared every kSampleInterval of simulated time up to the duration: the error of
// a run is its worst over the trajectory, so a phase error that happens to vanish at the end
// does not read as accuracy. Every dt of the study divides it.
constexpr Real kSampleInterval = 0.2;

// The positions at each sample time, the first at kSampleInterval.
using Trajectory = std::vector<Vec3Array>;

// A reference problem of the accuracy study: a scene, how long to run it, and the positions it
// must pass through (from a closed form, or from a run of RK4 at a tiny step).
struct ReferenceProblem {
  std::string name;
  std::string description;
  Real duration = 0.0;
  std::function<World(Integrator integrator, Real dt)> build;
  // Exact positions at time t, or empty to use a reference run.
  std::function<Vec3Array(Real t)> exact;
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

// A 1 kg particle on a 1 m rod to a fixed point, released from the horizontal.
ReferenceProblem rodPendulum();
// Five 1 kg particles joined by 1 m rods, the first to a fixed point, released horizontally: a
// rope that falls, folds and whips.
ReferenceProblem rodRope();

// A world stepping at dt with the integrator under the given gravity, and no frame-time cap below
// dt, for a problem's scene.
World emptyWorld(Integrator integrator, Real dt, const Vec3& gravity);

// Runs the scene to the problem's duration; returns the positions at every sample time.
Trajectory trajectory(const ReferenceProblem& problem, Integrator integrator, Real dt);
// The exact positions at every sample time, or a run of RK4 at dt = 1e-5 when there is no closed
// form.
Trajectory referenceTrajectory(const ReferenceProblem& problem);

}  // namespace study
}  // namespace mass_aggregate_sim
