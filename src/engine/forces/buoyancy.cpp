// The buoyancy kind (buoyancy.h): validation, force and its Jacobian.
#include "mass_aggregate_sim/engine/forces/buoyancy.h"

#include <cmath>

#include "engine/core/checks.h"
#include "engine/forces/force_evaluation.h"
#include "engine/forces/force_laws.h"
#include "engine/integrators/implicit_system.h"

namespace mass_aggregate_sim {
namespace engine {

Status ForceKind<Buoyancy>::validate(Buoyancy& buoyancy, const ParticleStore& particles) {
  const Status particle = particles.checkReference(buoyancy.particle, "particle");
  if (!particle) return particle;
  if (!finitePositive(buoyancy.max_depth)) return Status::error("max_depth must be finite and > 0");
  if (!finiteNonNegative(buoyancy.volume)) return Status::error("volume must be finite and >= 0");
  const Status liquid = checkLiquid(buoyancy.liquid_density, buoyancy.surface_height, buoyancy.up);
  if (!liquid) return liquid;
  buoyancy.up.normalize();
  return Status::ok();
}

void ForceKind<Buoyancy>::accumulate(const std::vector<Buoyancy>& buoyancies,
                                     const ForceEvaluation& e, Eigen::Ref<Vec3Array> force,
                                     Real* elastic) {
  for (const Buoyancy& buoyancy : buoyancies) {
    const std::size_t i = e.particles.denseIndexUnchecked(buoyancy.particle);
    const Real height = buoyancy.up.dot(e.x.col(i)) - buoyancy.surface_height;
    const Real submerged = submergedFraction(height, buoyancy.max_depth);
    if (submerged == 0.0) continue;
    const Real full = buoyancy.liquid_density * buoyancy.volume * e.gravity_magnitude;
    force.col(i) += full * submerged * buoyancy.up;
  }
}

void ForceKind<Buoyancy>::linearise(const std::vector<Buoyancy>& buoyancies,
                                    ImplicitSystem& system) {
  for (const Buoyancy& b : buoyancies) {
    const std::size_t a = system.index(b.particle);
    const Real height = b.up.dot(system.positions().col(a)) - b.surface_height;
    if (std::abs(height) >= b.max_depth) continue;
    // In the partly submerged band the force falls linearly with height.
    const Mat3 k =
        -(b.liquid_density * b.volume * system.gravityMagnitude() / (2.0 * b.max_depth)) * b.up *
        b.up.transpose();
    system.addSingle(a, k, Mat3::Zero());
  }
}

}  // namespace engine
}  // namespace mass_aggregate_sim
