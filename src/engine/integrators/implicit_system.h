#pragma once

#include <Eigen/Core>
#include <cstddef>

#include "mass_aggregate_sim/engine/core/particle_id.h"
#include "mass_aggregate_sim/engine/core/types.h"

namespace mass_aggregate_sim {
namespace engine {

using Mat3 = Eigen::Matrix3d;

// The linear system of implicit Euler as the force kinds see it (ForceKind::linearise): each adds
// the Jacobians of its forces at the start of the step, K = df/dx and D = df/dv, of one particle
// (addSingle) or of a pair acting equally and oppositely on two (addPair).
class ImplicitSystem {
 public:
  virtual ~ImplicitSystem() = default;
  virtual const Eigen::Ref<const Vec3Array>& positions() const = 0;
  virtual const Eigen::Ref<const Vec3Array>& velocities() const = 0;
  virtual Real gravityMagnitude() const = 0;
  virtual std::size_t index(ParticleId id) const = 0;
  virtual void addSingle(std::size_t a, const Mat3& k, const Mat3& d) = 0;
  virtual void addPair(std::size_t a, std::size_t b, const Mat3& k, const Mat3& d) = 0;
};

}  // namespace engine
}  // namespace mass_aggregate_sim
