// Classical Runge-Kutta with the damping integrated by its integrating factor: the classical
// stages on w = e^(-L t) y, L the damping (v' = ln(d) v), written with forward factors only
// (Lawson's form, fourth order; without damping, d^h = 1, the textbook stages to the bit).
#include "engine/integrators/integrators.h"
#include "engine/world/step_context.h"

namespace mass_aggregate_sim {
namespace engine {

void integrateRk4(StepContext& ctx) {
  ParticleStore& particles = ctx.particles;
  auto x = particles.positions();
  auto v = particles.velocities();
  const std::size_t n = particles.size();
  const Real h = ctx.h;
  const auto decay = ctx.caches.damping.decay;
  const auto half_decay = ctx.caches.damping.half_decay;
  Vec3Array& stage_acceleration = ctx.caches.stage_a[0];
  Vec3Array& velocity_sum = ctx.caches.stage_a[1];
  Vec3Array& acceleration_sum = ctx.integration.acceleration;
  Vec3Array& stage_x = ctx.caches.scratch_x;
  Vec3Array& stage_v = ctx.caches.scratch_v;
  stage_acceleration.resize(3, x.cols());
  velocity_sum.resize(3, x.cols());
  stage_x.resize(3, x.cols());
  stage_v.resize(3, x.cols());

  // k1 at (x, v)
  ctx.accelerations(x, v, stage_acceleration);
  velocity_sum = v;
  for (std::size_t i = 0; i < n; ++i) {
    acceleration_sum.col(i) = decay[i] * stage_acceleration.col(i);
    // k2 at (x + v h/2, d^(h/2) (v + a1 h/2))
    stage_x.col(i) = x.col(i) + (0.5 * h) * v.col(i);
    stage_v.col(i) = half_decay[i] * (v.col(i) + (0.5 * h) * stage_acceleration.col(i));
  }
  ctx.accelerations(stage_x, stage_v, stage_acceleration);
  velocity_sum += 2.0 * stage_v;
  for (std::size_t i = 0; i < n; ++i) {
    acceleration_sum.col(i) += 2.0 * (half_decay[i] * stage_acceleration.col(i));
    // k3 at (x + v2 h/2, d^(h/2) v + a2 h/2)
    stage_x.col(i) = x.col(i) + (0.5 * h) * stage_v.col(i);
    stage_v.col(i) = half_decay[i] * v.col(i) + (0.5 * h) * stage_acceleration.col(i);
  }
  ctx.accelerations(stage_x, stage_v, stage_acceleration);
  velocity_sum += 2.0 * stage_v;
  for (std::size_t i = 0; i < n; ++i) {
    acceleration_sum.col(i) += 2.0 * (half_decay[i] * stage_acceleration.col(i));
    // k4 at (x + v3 h, d^h v + d^(h/2) a3 h)
    stage_x.col(i) = x.col(i) + h * stage_v.col(i);
    stage_v.col(i) = decay[i] * v.col(i) + h * (half_decay[i] * stage_acceleration.col(i));
  }
  ctx.accelerations(stage_x, stage_v, stage_acceleration);
  velocity_sum += stage_v;
  acceleration_sum += stage_acceleration;

  // x' = x + h/6 (v1 + 2 v2 + 2 v3 + v4),
  // v' = d^h v + h/6 (d^h a1 + 2 d^(h/2) (a2 + a3) + a4)
  x += (h / 6.0) * velocity_sum;
  for (std::size_t i = 0; i < n; ++i) {
    v.col(i) = decay[i] * v.col(i) + (h / 6.0) * acceleration_sum.col(i);
  }
  acceleration_sum /= 6.0;  // the mean acceleration over the stages
}

}  // namespace engine
}  // namespace mass_aggregate_sim
