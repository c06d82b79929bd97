// Velocity Verlet, kick-drift-kick with the damping solved exactly in each half kick (a Strang
// splitting, second order with damping too):
//   v+ = d^(h/2) v + phi(h/2) a,  x' = x + v+ h,  v' = d^(h/2) v+ + phi(h/2) a'
// with a' evaluated at x' and the velocity v+ would reach with a held: d^(h/2) v+ + phi(h/2) a.
// a' is kept (without external forces) as the next substep's a while nothing changes.
#include "engine/integrators/integrators.h"
#include "engine/world/step_context.h"

namespace mass_aggregate_sim {
namespace engine {

void integrateVelocityVerlet(StepContext& ctx) {
  ParticleStore& particles = ctx.particles;
  IntegratorState& state = ctx.integration;
  const DampingFactors& damping = ctx.caches.damping;
  const Real h = ctx.h;
  auto x = particles.positions();
  auto v = particles.velocities();
  const std::size_t n = particles.size();
  if (!state.acceleration_valid) {
    state.internal_acceleration.resize(3, x.cols());
    ctx.accelerations(x, v, state.internal_acceleration, /*external=*/false);
  }
  const bool external = ctx.scene.external;
  Vec3Array& external_acceleration = ctx.caches.stage_a[1];
  if (external) ctx.externalAccelerations(external_acceleration);
  const auto total = [&](const Vec3Array& internal, const std::size_t i) -> Vec3 {
    return external ? Vec3(internal.col(i) + external_acceleration.col(i)) : Vec3(internal.col(i));
  };
  Vec3Array& predicted = ctx.caches.scratch_v;
  predicted.resize(3, x.cols());
  for (std::size_t i = 0; i < n; ++i) {
    const Real half_decay = damping.half_decay[i];
    const Real half_gain = damping.half_gain[i];
    const Vec3 a = total(state.internal_acceleration, i);
    const Vec3 half = half_decay * v.col(i) + half_gain * a;
    x.col(i) += h * half;
    v.col(i) = half;
    predicted.col(i) = half_decay * half + half_gain * a;
  }
  Vec3Array& next_internal = ctx.caches.stage_a[0];
  next_internal.resize(3, x.cols());
  ctx.accelerations(x, predicted, next_internal, /*external=*/false);
  for (std::size_t i = 0; i < n; ++i) {
    // v' = d^(h/2) v_half + phi(h/2) a'
    const Vec3 next = total(next_internal, i);
    v.col(i) = damping.half_decay[i] * v.col(i) + damping.half_gain[i] * next;
    state.acceleration.col(i) = next;
  }
  state.internal_acceleration.swap(next_internal);
  state.acceleration_valid = true;
}

}  // namespace engine
}  // namespace mass_aggregate_sim
