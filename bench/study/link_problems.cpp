// The study's problems with rods: the particle solver's links under each integrator.
#include <cmath>

#include "mass_aggregate_sim/engine/solver/rod.h"
#include "reference_problems.h"

namespace mass_aggregate_sim {
namespace study {
namespace {

using engine::ParticleId;
using engine::ParticleSpec;
using engine::Rod;

constexpr Real kG = 9.81;
constexpr Real kLength = 1.0;

// Unit masses at (L, 0, 0), (2 L, 0, 0), ... joined by rods of length L, the first to the origin.
World rope(const Integrator integrator, const Real dt, const int knots) {
  World world = emptyWorld(integrator, dt, Vec3(0.0, -kG, 0.0));
  ParticleId previous;
  for (int i = 0; i < knots; ++i) {
    ParticleSpec spec;
    spec.position = Vec3((i + 1) * kLength, 0.0, 0.0);
    const ParticleId id = world.addParticle(spec).value();
    world.addLink(i == 0 ? Rod::anchoredAt(id, Vec3::Zero(), kLength)
                         : Rod::between(previous, id, kLength));
    previous = id;
  }
  return world;
}

// The pendulum's angle from the downward vertical, theta'' = -(g / L) sin(theta), from
// theta = pi / 2 at rest, by RK4 at a step of 1e-4 s (its error about 1e-16 rad).
Real pendulumAngle(const Real t) {
  constexpr Real kStep = 1e-4;
  const auto acceleration = [](const Real theta) { return -kG / kLength * std::sin(theta); };
  Real theta = 0.5 * M_PI;
  Real omega = 0.0;
  const long steps = std::lround(t / kStep);
  for (long s = 0; s < steps; ++s) {
    const Real k1x = omega;
    const Real k1v = acceleration(theta);
    const Real k2x = omega + 0.5 * kStep * k1v;
    const Real k2v = acceleration(theta + 0.5 * kStep * k1x);
    const Real k3x = omega + 0.5 * kStep * k2v;
    const Real k3v = acceleration(theta + 0.5 * kStep * k2x);
    const Real k4x = omega + kStep * k3v;
    const Real k4v = acceleration(theta + kStep * k3x);
    theta += kStep / 6.0 * (k1x + 2.0 * k2x + 2.0 * k3x + k4x);
    omega += kStep / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
  }
  return theta;
}

}  // namespace

ReferenceProblem rodPendulum() {
  ReferenceProblem p;
  p.name = "rod_pendulum";
  p.description = "unit mass on an anchored 1 m rod released horizontally, 5 s, exact solution";
  p.duration = 5.0;
  p.build = [](const Integrator integrator, const Real dt) { return rope(integrator, dt, 1); };
  p.exact = [](const Real t) {
    const Real theta = pendulumAngle(t);
    Vec3Array x(3, 1);
    x.col(0) = kLength * Vec3(std::sin(theta), -std::cos(theta), 0.0);
    return x;
  };
  return p;
}

ReferenceProblem rodRope() {
  ReferenceProblem p;
  p.name = "rod_rope";
  p.description =
      "five unit masses on 1 m rods, the first anchored, released horizontally, 3 s, "
      "vs RK4 dt 1e-5";
  p.duration = 3.0;
  p.build = [](const Integrator integrator, const Real dt) { return rope(integrator, dt, 5); };
  return p;
}

}  // namespace study
}  // namespace mass_aggregate_sim
