#pragma once

#include <vector>

#include "mass_aggregate_sim/engine/bodies/body_spec.h"
#include "mass_aggregate_sim/engine/core/status.h"

namespace mass_aggregate_sim {
namespace engine {

// Mass, centre of mass and principal inertia of a set of shapes in a body's frame.
struct MassProperties {
  Real mass = 0.0;    // kg
  Real volume = 0.0;  // m^3
  // The mass frame: the centre of mass and the principal axes, as a pose in the body's frame.
  Transform frame;
  Vec3 principal_inertia = Vec3::Zero();  // kg m^2 about the principal axes
};

// The shapes' mass properties: each shape's mass from its density (or all scaled so that they sum
// to `mass` when it is > 0), moved to the common centre of mass by the parallel-axis theorem
//   I_c = sum_k R_k I_k R_k^T + m_k (|d_k|^2 E - d_k d_k^T),  d_k = c_k - c,
// then diagonalised (a tensor that is diagonal already keeps its axes exactly). Refused when the
// shapes are invalid, their mass is not finite and > 0, or the tensor is not positive definite.
Result<MassProperties> computeMassProperties(const std::vector<BodyShapeSpec>& shapes, Real mass);

}  // namespace engine
}  // namespace mass_aggregate_sim
