#pragma once

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <optional>
#include <vector>

#include "engine/integrators/implicit_system.h"
#include "mass_aggregate_sim/engine/core/particle_store.h"
#include "mass_aggregate_sim/engine/core/types.h"
#include "mass_aggregate_sim/engine/forces/force_generators.h"

namespace mass_aggregate_sim {
namespace engine {

// Linearised backward Euler (Baraff and Witkin): with K = df/dx and D = df/dv at the start of the
// step, f(x + dx, v + dv) ~ f0 + K dx + D dv and dx = h (v + dv), so
//   (M - h D - h^2 K) dv = h (f0 + h K v).
// Each force kind adds its own K and D (ForceKind::linearise), the particle damping m ln(d) I
// joins D and f0 (so backward Euler solves it too); springs clamp their transverse
// stiffness so the matrix stays symmetric positive definite, and one sparse Cholesky solve gives
// dv.
class ImplicitEulerSolver : public ImplicitSystem {
 public:
  // acceleration: the full acceleration at the step start, so M a = f0. Fills dv for every
  // particle (zero for immovable ones). Returns false when the factorisation failed.
  bool solve(const ForceGenerators& generators, const ParticleStore& particles,
             const Eigen::Ref<const Vec3Array>& acceleration, Real gravity_magnitude, Real h,
             Eigen::Ref<Vec3Array> dv);

  const Eigen::Ref<const Vec3Array>& positions() const override { return *x_; }
  const Eigen::Ref<const Vec3Array>& velocities() const override { return *v_; }
  Real gravityMagnitude() const override { return gravity_magnitude_; }
  std::size_t index(ParticleId id) const override { return particles_->denseIndexUnchecked(id); }
  // The matrix gets -h D - h^2 K; rows and columns of immovable particles are left out (their dv
  // is zero), which is also why K v needs no terms from them (their v is zero).
  void addSingle(std::size_t a, const Mat3& k, const Mat3& d) override;
  // K = dF_a/dx_a and D = dF_a/dv_a of a pair with F_b = -F_a.
  void addPair(std::size_t a, std::size_t b, const Mat3& k, const Mat3& d) override;

 private:
  void addBlock(std::size_t row, std::size_t col, const Mat3& block);

  const ParticleStore* particles_ = nullptr;
  std::optional<Eigen::Ref<const Vec3Array>> x_;
  std::optional<Eigen::Ref<const Vec3Array>> v_;
  Real gravity_magnitude_ = 0.0;
  Real h_ = 0.0;
  Vec3Array stiffness_times_v_;
  ScalarArray movable_;
  ScalarArray damping_rate_;  // ln(d) per particle (0 for d = 0, held still instead)

  std::vector<Eigen::Triplet<Real>> triplets_;
  Eigen::SparseMatrix<Real> matrix_;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<Real>> solver_;
  Eigen::VectorXd rhs_;
};

}  // namespace engine
}  // namespace mass_aggregate_sim
