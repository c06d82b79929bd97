#include "reference_problems.h"

#include <cmath>

namespace mass_aggregate_sim {
namespace study {
namespace {

using engine::Drag;
using engine::ParticleId;
using engine::ParticleSpec;
using engine::Spring;
using engine::WorldConfig;

constexpr Real kZeta = 0.1;

// A unit mass on a spring of rest length 0 to the origin, released at x = 1: along x the force
// is -(k x + c v), the linear oscillator.
World oscillator(const Integrator integrator, const Real dt, const Real damping) {
  World world = emptyWorld(integrator, dt, Vec3::Zero());
  ParticleSpec spec;
  spec.position = Vec3::UnitX();
  const ParticleId id = world.addParticle(spec).value();
  Spring spring;
  spring.a = id;
  spring.stiffness = 1.0;
  spring.damping = damping;
  world.addGenerator(spring);
  return world;
}

Vec3Array singlePoint(const Real x) {
  Vec3Array p(3, 1);
  p.col(0) = Vec3(x, 0.0, 0.0);
  return p;
}

}  // namespace

World emptyWorld(const Integrator integrator, const Real dt, const Vec3& gravity) {
  WorldConfig config;
  config.dt = dt;
  config.integrator = integrator;
  config.gravity = gravity;
  config.max_frame_time = std::max(0.25, dt);
  return World(config);
}

ReferenceProblem undampedOscillator() {
  ReferenceProblem p;
  p.name = "undamped_oscillator";
  p.description = "undamped harmonic oscillator, omega = 1, 10 s, exact solution";
  p.duration = 10.0;
  p.build = [](const Integrator integrator, const Real dt) {
    return oscillator(integrator, dt, 0.0);
  };
  p.exact = [](const Real t) { return singlePoint(std::cos(t)); };
  return p;
}

ReferenceProblem dampedOscillator() {
  ReferenceProblem p;
  p.name = "damped_oscillator";
  p.description = "damped harmonic oscillator, omega = 1, zeta = 0.1, 10 s, exact solution";
  p.duration = 10.0;
  p.build = [](const Integrator integrator, const Real dt) {
    return oscillator(integrator, dt, 2.0 * kZeta);  // c = 2 zeta omega m
  };
  p.exact = [](const Real t) {
    const Real wd = std::sqrt(1.0 - kZeta * kZeta);
    return singlePoint(std::exp(-kZeta * t) * (std::cos(wd * t) + kZeta / wd * std::sin(wd * t)));
  };
  return p;
}

ReferenceProblem springChain() {
  ReferenceProblem p;
  p.name = "spring_chain";
  p.description = "10-particle spring chain (k = 100) swinging under gravity, 5 s, vs RK4 dt 1e-5";
  p.duration = 5.0;
  p.build = [](const Integrator integrator, const Real dt) {
    World world = emptyWorld(integrator, dt, Vec3(0.0, -9.81, 0.0));
    ParticleId previous;
    for (int i = 0; i < 10; ++i) {
      ParticleSpec spec;
      spec.position = Vec3(i + 1.0, 0.0, 0.0);
      const ParticleId id = world.addParticle(spec).value();
      if (i == 0) {
        Spring anchor;
        anchor.a = id;
        anchor.stiffness = 100.0;
        anchor.rest_length = 1.0;
        world.addGenerator(anchor);
      } else {
        Spring spring;
        spring.a = previous;
        spring.b = id;
        spring.stiffness = 100.0;
        spring.rest_length = 1.0;
        world.addGenerator(spring);
      }
      previous = id;
    }
    return world;
  };
  return p;
}

ReferenceProblem dragProjectile() {
  ReferenceProblem p;
  p.name = "drag_projectile";
  p.description = "projectile with quadratic drag (k2 = 0.05), 4 s, vs RK4 dt 1e-5";
  p.duration = 4.0;
  p.build = [](const Integrator integrator, const Real dt) {
    World world = emptyWorld(integrator, dt, Vec3(0.0, -9.81, 0.0));
    ParticleSpec spec;
    spec.velocity = Vec3(30.0, 30.0, 0.0);
    const ParticleId id = world.addParticle(spec).value();
    Drag drag;
    drag.particle = id;
    drag.k2 = 0.05;
    world.addGenerator(drag);
    return world;
  };
  return p;
}

ReferenceProblem dampedProjectile() {
  constexpr Real kDamping = 0.5;
  const Vec3 x0(0.0, 1.5, 0.0);
  const Vec3 v0(40.0, 30.0, 0.0);
  const Vec3 g(0.0, -20.0, 0.0);
  ReferenceProblem p;
  p.name = "damped_projectile";
  p.description = "the seeds' projectile with particle damping 0.5, 4 s, exact solution";
  p.duration = 4.0;
  p.build = [=](const Integrator integrator, const Real dt) {
    World world = emptyWorld(integrator, dt, g);
    ParticleSpec spec;
    spec.position = x0;
    spec.velocity = v0;
    spec.inverse_mass = 1.0 / 200.0;
    spec.damping = kDamping;
    world.addParticle(spec);
    return world;
  };
  p.exact = [=](const Real t) {
    const Real lambda = std::log(kDamping);
    const Real phi = std::expm1(lambda * t) / lambda;
    Vec3Array x(3, 1);
    x.col(0) = x0 + phi * v0 + (phi - t) / lambda * g;
    return x;
  };
  return p;
}

Trajectory trajectory(const ReferenceProblem& problem, const Integrator integrator, const Real dt) {
  World world = problem.build(integrator, dt);
  const long samples = std::lround(problem.duration / kSampleInterval);
  const long steps_per_sample = std::lround(kSampleInterval / dt);
  Trajectory positions;
  positions.reserve(samples);
  for (long k = 0; k < samples; ++k) {
    for (long s = 0; s < steps_per_sample; ++s) world.step();
    positions.push_back(world.particles().positions());
  }
  return positions;
}

Trajectory referenceTrajectory(const ReferenceProblem& problem) {
  if (!problem.exact) return trajectory(problem, Integrator::kRk4, 1e-5);
  Trajectory positions;
  const long samples = std::lround(problem.duration / kSampleInterval);
  for (long k = 1; k <= samples; ++k) positions.push_back(problem.exact(k * kSampleInterval));
  return positions;
}

}  // namespace study
}  // namespace mass_aggregate_sim
