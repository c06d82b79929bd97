// The drag kind (drag.h): validation, force and its Jacobian.
#include "mass_aggregate_sim/engine/forces/drag.h"

#include "engine/core/checks.h"
#include "engine/forces/force_evaluation.h"
#include "engine/forces/force_laws.h"
#include "engine/integrators/implicit_system.h"

namespace mass_aggregate_sim {
namespace engine {

Status ForceKind<Drag>::validate(Drag& drag, const ParticleStore& particles) {
  const Status particle = particles.checkReference(drag.particle, "particle");
  if (!particle) return particle;
  if (!finiteNonNegative(drag.k1) || !finiteNonNegative(drag.k2)) {
    return Status::error("drag coefficients k1 and k2 must be finite and >= 0");
  }
  return Status::ok();
}

void ForceKind<Drag>::accumulate(const std::vector<Drag>& drags, const ForceEvaluation& e,
                                 Eigen::Ref<Vec3Array> force, Real* elastic) {
  for (const Drag& drag : drags) {
    const std::size_t i = e.particles.denseIndexUnchecked(drag.particle);
    force.col(i) += dragForce(e.v.col(i), drag.k1, drag.k2);
  }
}

void ForceKind<Drag>::decay(const std::vector<Drag>& drags, const ParticleStore& particles,
                            std::vector<DecayTerm>& terms) {
  // -k1 v alone: the k2 |v| v part's rate grows with the speed, which no state-free bound holds.
  const auto inverse_mass = particles.inverseMasses();
  for (const Drag& drag : drags) {
    const auto i = static_cast<Eigen::Index>(particles.denseIndexUnchecked(drag.particle));
    terms.push_back(DecayTerm{drag.id, drag.k1 * inverse_mass[i], false});
  }
}

void ForceKind<Drag>::linearise(const std::vector<Drag>& drags, ImplicitSystem& system) {
  for (const Drag& drag : drags) {
    const std::size_t a = system.index(drag.particle);
    const Vec3 va = system.velocities().col(a);
    const Real speed = va.norm();
    // d/dv of -(k1 + k2 |v|) v = -(k1 + k2 |v|) I - k2 v v^T / |v|
    Mat3 d = -(drag.k1 + drag.k2 * speed) * Mat3::Identity();
    if (speed > 0.0) d -= drag.k2 * va * va.transpose() / speed;
    system.addSingle(a, Mat3::Zero(), d);
  }
}

}  // namespace engine
}  // namespace mass_aggregate_sim
