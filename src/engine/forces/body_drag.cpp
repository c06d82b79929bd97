// The body drag kind (body_drag.h): validation and force.
#include "mass_aggregate_sim/engine/forces/body_drag.h"

#include "engine/core/checks.h"
#include "engine/forces/body_force_stage.h"
#include "engine/forces/force_laws.h"

namespace mass_aggregate_sim {
namespace engine {

Status BodyForceKind<BodyDrag>::validate(BodyDrag& drag, const JointScene& scene) {
  const Status body = scene.bodies.checkReference(drag.body, "body");
  if (!body) return body;
  if (!finiteNonNegative(drag.k1) || !finiteNonNegative(drag.k2)) {
    return Status::error("drag coefficients k1 and k2 must be finite and >= 0");
  }
  if (!finiteNonNegative(drag.angular)) {
    return Status::error("angular drag must be finite and >= 0");
  }
  return Status::ok();
}

void BodyForceKind<BodyDrag>::accumulate(const std::vector<BodyDrag>& drags,
                                         const BodyForceScene& scene, BodyForceSums& sums) {
  for (const BodyDrag& drag : drags) {
    const ForceEnd centre = scene.centre(drag.body);
    sums.add(centre, dragForce(centre.velocity, drag.k1, drag.k2));
    // T = -angular w
    sums.addTorque(centre, -drag.angular * scene.angularVelocity(drag.body));
  }
}

// -k1 v on the mass, -angular w about the axis of least inertia (the fastest to decay).
void BodyForceKind<BodyDrag>::decay(const std::vector<BodyDrag>& drags, const BodyForceScene& scene,
                                    std::vector<DecayTerm>& terms) {
  const BodyStore& bodies = scene.bodies();
  for (const BodyDrag& drag : drags) {
    const std::size_t i = bodies.denseIndexUnchecked(drag.body);
    terms.push_back(DecayTerm{drag.id, drag.k1 * bodies.inverseMass(i), false});
    terms.push_back(
        DecayTerm{drag.id, drag.angular * bodies.inversePrincipalInertia(i).maxCoeff(), true});
  }
}

}  // namespace engine
}  // namespace mass_aggregate_sim
