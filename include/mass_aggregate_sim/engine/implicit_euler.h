#pragma once

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <vector>

#include "mass_aggregate_sim/engine/force_generators.h"
#include "mass_aggregate_sim/engine/particle_store.h"
#include "mass_aggregate_sim/engine/types.h"

namespace mass_aggregate_sim {
namespace engine {

// Linearised backward Euler (Baraff and Witkin): with K = df/dx and D = df/dv at the start of the
// step, f(x + dx, v + dv) ~ f0 + K dx + D dv and dx = h (v + dv), so
//   (M - h D - h^2 K) dv = h (f0 + h K v).
// Springs, bungees, drag and buoyancy enter K and D; their transverse stiffness is clamped so the
// matrix stays symmetric positive definite, and one sparse Cholesky solve gives dv.
class ImplicitEulerSolver {
 public:
  // acceleration: the full acceleration at the step start, so M a = f0. Fills dv for every
  // particle (zero for immovable ones). Returns false when the factorisation failed.
  bool solve(const ForceGenerators& generators, const ParticleStore& particles,
             const Eigen::Ref<const Vec3Array>& acceleration, Real gravity_magnitude, Real h,
             Eigen::Ref<Vec3Array> dv);

 private:
  // Adds a pair term with K = dF_a/dx_a and D = dF_a/dv_a (F_b = -F_a) to the matrix and K v.
  void addPair(std::size_t a, std::size_t b, const Eigen::Matrix3d& k, const Eigen::Matrix3d& d,
               const Eigen::Ref<const Vec3Array>& v, Real h);
  void addSingle(std::size_t a, const Eigen::Matrix3d& k, const Eigen::Matrix3d& d,
                 const Eigen::Ref<const Vec3Array>& v, Real h);
  void addBlock(std::size_t row, std::size_t col, const Eigen::Matrix3d& block);

  Vec3Array stiffness_times_v_;
  ScalarArray movable_;

  std::vector<Eigen::Triplet<Real>> triplets_;
  Eigen::SparseMatrix<Real> matrix_;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<Real>> solver_;
  Eigen::VectorXd rhs_;
};

}  // namespace engine
}  // namespace mass_aggregate_sim
