// Position Verlet: x' = 2x - x_prev + a h^2 undamped, each particle keeping its own history
// (previous position and external acceleration, ParticleStore). With damping the two half kicks
// the recurrence merges are the damped ones of velocity Verlet (second order).
#include "engine/integrators/integrators.h"
#include "engine/world/step_context.h"

namespace mass_aggregate_sim {
namespace engine {

void seedVerletHistory(ParticleStore& particles, const DampingFactors& damping, const std::size_t i,
                       const Real h, const Vec3& behind) {
  auto previous = particles.previousPositions();
  const auto x = particles.positions();
  const auto v = particles.velocities();
  const Real half_decay = damping.half_decay[i];
  if (half_decay == 0.0) {
    // d = 0 keeps no velocity: the next position is x whatever the history says.
    previous.col(i) = x.col(i);
    return;
  }
  previous.col(i) = x.col(i) - h * ((v.col(i) - damping.half_gain[i] * behind) / half_decay);
}

bool keepsVerletHistory(const StepContext& ctx) {
  return ctx.config.integrator == Integrator::kPositionVerlet &&
         ctx.integration.verlet_history_h == ctx.h;
}

void reseedVerletHistory(StepContext& ctx, const std::size_t i) {
  seedVerletHistory(ctx.particles, ctx.caches.damping, i, ctx.h,
                    ctx.integration.acceleration.col(static_cast<Eigen::Index>(i)));
}

void integratePositionVerlet(StepContext& ctx) {
  ParticleStore& particles = ctx.particles;
  IntegratorState& state = ctx.integration;
  const DampingFactors& damping = ctx.caches.damping;
  const Real h = ctx.h;
  auto x = particles.positions();
  auto v = particles.velocities();
  auto previous = particles.previousPositions();
  auto previous_external = particles.previousExternalAccelerations();
  auto seeded = particles.historySeeded();
  const std::size_t n = particles.size();
  // The forces continuous in time (generators, gravity, own accelerations) at the start of the
  // step, and the external ones, constant over the step.
  Vec3Array& acceleration = state.acceleration;
  ctx.accelerations(x, v, acceleration, /*external=*/false);
  const bool external = ctx.scene.external || state.external_in_history;
  Vec3Array& external_acceleration = ctx.caches.stage_a[1];
  if (external) ctx.externalAccelerations(external_acceleration);
  if (state.verlet_history_h != h) {
    seeded.setZero();
    state.verlet_unseeded = true;
  }
  if (state.verlet_unseeded) {
    for (std::size_t i = 0; i < n; ++i) {
      if (seeded[i] != 0.0) continue;
      seedVerletHistory(particles, damping, i, h, acceleration.col(i));
      previous_external.col(i).setZero();
      seeded[i] = 1.0;
    }
    state.verlet_unseeded = false;
  }
  for (std::size_t i = 0; i < n; ++i) {
    const Real decay = damping.decay[i];
    const Real half_decay = damping.half_decay[i];
    const Real half_gain = damping.half_gain[i];
    const Vec3 current = x.col(i);
    const Vec3 a = acceleration.col(i);
    // Leapfrog with the damped half kicks merged: v_half' = d^h v_half + kick, where the kick
    // holds the continuous forces' half kicks at both ends of the step (a at its start stands
    // for both) and the external forces of the last step's second half and of this step's first.
    // Undamped: x' = 2x - x_prev + a h^2 (+ the external forces' average times h^2).
    Vec3 kick = (1.0 + half_decay) * a;
    Vec3 last_half = a;
    if (external) {
      const Vec3 e = external_acceleration.col(i);
      kick += half_decay * previous_external.col(i) + e;
      last_half += e;
      previous_external.col(i) = e;
    }
    const Vec3 next = current + decay * (current - previous.col(i)) + h * (half_gain * kick);
    // v' = d^(h/2) (x' - x)/h + phi(h/2) (a + e): the last half kick, with the continuous forces
    // of the start of the step standing for those of its end (second order).
    v.col(i) = half_decay * ((next - current) / h) + half_gain * last_half;
    previous.col(i) = current;
    x.col(i) = next;
    acceleration.col(i) = last_half;
  }
  state.external_in_history = ctx.scene.external;
  state.verlet_history_h = h;
}

}  // namespace engine
}  // namespace mass_aggregate_sim
