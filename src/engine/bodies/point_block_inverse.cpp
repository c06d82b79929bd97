#include "engine/bodies/point_block_inverse.h"

#include <Eigen/Eigenvalues>
#include <cmath>

namespace mass_aggregate_sim {
namespace engine {
namespace {

// K^+ = V diag(1 / l_i, 0 below the floor) V^T from K = V diag(l) V^T.
template <int N>
Eigen::Matrix<Real, N, N> pseudoInverseByEigenvalues(const Eigen::Matrix<Real, N, N>& k) {
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix<Real, N, N>> eigen;
  if constexpr (N <= 3) {
    eigen.computeDirect(k);
  } else {
    eigen.compute(k);
  }
  const auto& values = eigen.eigenvalues();
  const Real floor = kPseudoInverseFloor * values.cwiseAbs().maxCoeff();
  Eigen::Matrix<Real, N, 1> inverted;
  for (int i = 0; i < N; ++i) inverted[i] = values[i] > floor ? 1.0 / values[i] : 0.0;
  return eigen.eigenvectors() * inverted.asDiagonal() * eigen.eigenvectors().transpose();
}

// Two points in closed form: the eigenvalues of [[a, b], [b, c]] are m +- r (m = (a + c) / 2,
// r = sqrt(((a - c) / 2)^2 + b^2)); both above the floor, the inverse
// [[c, -b], [-b, a]] / (a c - b^2); else only the larger, along its eigenvector u: u u^T / (m + r).
SmallBlock pseudoInverseOfTwo(const SmallBlock& k) {
  const Real a = k(0, 0);
  const Real b = k(0, 1);
  const Real c = k(1, 1);
  const Real m = 0.5 * (a + c);
  const Real half_gap = 0.5 * (a - c);
  const Real r = std::sqrt(half_gap * half_gap + b * b);
  const Real large = m + r;
  const Real small = m - r;
  SmallBlock inverse = SmallBlock::Zero(2, 2);
  if (large <= 0.0) return inverse;
  if (small > kPseudoInverseFloor * large) {
    const Real det = a * c - b * b;
    inverse << c / det, -b / det, -b / det, a / det;
    return inverse;
  }
  // (K - large I) u = 0: u along (b, large - a), or (large - c, b), whichever is longer.
  Eigen::Vector2d u(b, large - a);
  const Eigen::Vector2d other(large - c, b);
  if (other.squaredNorm() > u.squaredNorm()) u = other;
  if (u.squaredNorm() == 0.0) u = Eigen::Vector2d(1.0, 0.0);
  u.normalize();
  inverse = (u * u.transpose()) / large;
  return inverse;
}

}  // namespace

bool invertWellConditioned(const Mat3& k, Mat3& inverse) {
  const Real trace = k.trace();
  const Vec3 c12 = k.col(1).cross(k.col(2));
  const Real det = k.col(0).dot(c12);
  if (!(trace > 0.0) || !(det > kPseudoInverseFloor * trace * trace * trace)) return false;
  // K^-1 = adj(K) / det: adj's rows are the cross products of K's columns.
  inverse.row(0) = c12 / det;
  inverse.row(1) = k.col(2).cross(k.col(0)) / det;
  inverse.row(2) = k.col(0).cross(k.col(1)) / det;
  return true;
}

Mat3 pseudoInverse(const Mat3& k) {
  Mat3 inverse;
  if (invertWellConditioned(k, inverse)) return inverse;
  return pseudoInverseByEigenvalues<3>(k);
}

SmallBlock pseudoInverse(const SmallBlock& k) {
  switch (k.rows()) {
    case 1:
      return SmallBlock::Constant(1, 1, k(0, 0) > 0.0 ? 1.0 / k(0, 0) : 0.0);
    case 2:
      return pseudoInverseOfTwo(k);
    case 3:
      return pseudoInverse(Mat3(k));
    default:
      return pseudoInverseByEigenvalues<4>(Eigen::Matrix<Real, 4, 4>(k));
  }
}

}  // namespace engine
}  // namespace mass_aggregate_sim
