#pragma once
// How a rigid body moves over a substep h: semi-implicit Euler (the body solver's impulses act on
// the velocities, then the positions follow the new velocities), the orientation by the exponential
// map, and the gyroscopic term w x I w implicitly (the midpoint rule).

#include "mass_aggregate_sim/engine/core/transform.h"

namespace mass_aggregate_sim {
namespace engine {

// The rotation by w over h: exp(h w / 2) as a unit quaternion (axis w / |w|, angle |w| h).
Quat rotationOver(const Vec3& w, Real h);

// The seeds' first-order update, q + h/2 (0, w) q, normalised: the reference the exponential map
// is tested against (both agree to O(h^2) per step).
Quat firstOrderRotation(const Quat& q, const Vec3& w, Real h);

// The angular velocity after a substep of torque-free rotation with principal inertia `inertia`,
// from w_body (both in the principal frame), by the implicit midpoint rule on Euler's equations,
//   I (w' - w) + h m x (I m) = 0,  m = (w + w') / 2,
// solved by Newton's method (J = I + h/2 (skew(m) I - skew(I m))) to round-off. The midpoint rule
// keeps every quadratic invariant of the equations, so |I w| and w.I w (the length of the angular
// momentum and the energy) are conserved to round-off, and the intermediate-axis flip happens on
// time. The positions stage turns the body by w' itself, which leaves w' unchanged in the body
// frame (so the body-frame map is the midpoint's, exactly); the momentum's direction in the world
// then drifts by O(h) (2.4e-3 relative over 20 s of intermediate-axis flips at 240 Hz).
Vec3 gyroscopicStep(const Vec3& w_body, const Vec3& inertia, Real h);

}  // namespace engine
}  // namespace mass_aggregate_sim
