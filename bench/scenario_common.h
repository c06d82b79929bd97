#pragma once
// The common set-up of issue 5's benchmark scenarios: dt = 1/60 s, mass 1 kg, damping 0.99,
// gravity (0, -9.81, 0), particle radius 0.1 m.

#include "mass_aggregate_sim/engine/world.h"

namespace mass_aggregate_sim {
namespace engine {
namespace bench {

constexpr Real kDt = 1.0 / 60.0;
constexpr Real kDamping = 0.99;
constexpr Real kRadius = 0.1;

inline WorldConfig scenarioConfig(const Integrator integrator = Integrator::kSemiImplicitEuler) {
  WorldConfig config;
  config.dt = kDt;
  config.integrator = integrator;
  config.gravity = Vec3(0.0, -9.81, 0.0);
  return config;
}

inline ParticleSpec unitParticle(const Vec3& position) {
  ParticleSpec spec;
  spec.position = position;
  spec.inverse_mass = 1.0;
  spec.damping = kDamping;
  spec.radius = kRadius;
  return spec;
}

}  // namespace bench
}  // namespace engine
}  // namespace mass_aggregate_sim
