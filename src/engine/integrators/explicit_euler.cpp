// Explicit Euler: x' = x + v h, v' = (v + a h) d^h. First order; kept for teaching and comparison
// (unstable on every undamped spring).
#include "engine/integrators/integrators.h"
#include "engine/world/step_context.h"

namespace mass_aggregate_sim {
namespace engine {

void integrateExplicitEuler(StepContext& ctx) {
  auto x = ctx.particles.positions();
  auto v = ctx.particles.velocities();
  Vec3Array& a = ctx.integration.acceleration;
  ctx.accelerations(x, v, a);
  const auto decay = ctx.caches.damping.decay;
  const Real h = ctx.h;
  for (std::size_t i = 0; i < ctx.particles.size(); ++i) {
    // x' = x + v h,  v' = (v + a h) d^h
    x.col(i) += v.col(i) * h;
    v.col(i) = (v.col(i) + a.col(i) * h) * decay[i];
  }
}

}  // namespace engine
}  // namespace mass_aggregate_sim
