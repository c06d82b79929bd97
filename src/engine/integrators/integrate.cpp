#include "engine/forces/stiff_spring_stage.h"
#include "engine/integrators/integrators.h"
#include "engine/world/step_context.h"

namespace mass_aggregate_sim {
namespace engine {

void integrate(StepContext& ctx) {
  switch (ctx.config.integrator) {
    case Integrator::kExplicitEuler:
      return integrateExplicitEuler(ctx);
    case Integrator::kSemiImplicitEuler:
      return integrateSemiImplicitEuler(ctx);
    case Integrator::kPositionVerlet:
      return integratePositionVerlet(ctx);
    case Integrator::kVelocityVerlet:
      return integrateVelocityVerlet(ctx);
    case Integrator::kRk4:
      return integrateRk4(ctx);
    case Integrator::kImplicitEuler:
      return integrateImplicitEuler(ctx);
  }
}

void integrateVelocities(StepContext& ctx) {
  integrate(ctx);
  if (ctx.caches.stiff.empty()) return;
  applyStiffSprings(ctx.caches.stiff, ctx.particles, ctx.h);
  ctx.integration.verlet_unseeded = true;
  // Velocity Verlet's forces at the end of the substep saw the particles before this.
  ctx.integration.acceleration_valid = false;
}

Real positionWeight(const Integrator integrator) {
  switch (integrator) {
    case Integrator::kExplicitEuler:
      return 0.0;
    case Integrator::kSemiImplicitEuler:
    case Integrator::kImplicitEuler:
      return 1.0;
    case Integrator::kPositionVerlet:
    case Integrator::kVelocityVerlet:
    case Integrator::kRk4:
      return 0.5;
  }
  return 0.0;
}

}  // namespace engine
}  // namespace mass_aggregate_sim
