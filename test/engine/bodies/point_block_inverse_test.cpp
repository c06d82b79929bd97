// The pseudo-inverses of the blocks that couple a manifold's points: the adjugate shortcut is
// taken only where every eigenvalue is above the floor, and gives what the eigenvalues give.
#include "engine/bodies/point_block_inverse.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <random>

namespace mass_aggregate_sim {
namespace engine {
namespace {

struct Block {
  Mat3 k;
  Vec3 ratios;  // l / l_max, as built
  Real smallestRatio() const { return ratios.minCoeff(); }
  // Whether an eigenvalue is so close to the floor that its side of it is rounding's to decide.
  bool nearTheFloor() const {
    return (ratios.array() > 0.1 * kPseudoInverseFloor &&
            ratios.array() < 10.0 * kPseudoInverseFloor)
        .any();
  }
};

// K = R diag(l) R^T, R a random rotation, l_max = 1 and the other two 10^-u, u uniform in
// [0, 9]: from well conditioned to below the floor.
Block randomBlock(std::mt19937_64& random) {
  std::uniform_real_distribution<Real> unit(-1.0, 1.0);
  std::uniform_real_distribution<Real> exponent(0.0, 9.0);
  const Quat q = Quat(unit(random), unit(random), unit(random), unit(random)).normalized();
  const Mat3 r = q.toRotationMatrix();
  const Vec3 l(1.0, std::pow(10.0, -exponent(random)), std::pow(10.0, -exponent(random)));
  return {r * l.asDiagonal() * r.transpose(), l};
}

Mat3 byEigenvalues(const Mat3& k) {
  Eigen::SelfAdjointEigenSolver<Mat3> eigen(k);
  const Vec3& l = eigen.eigenvalues();
  Vec3 inverted;
  for (int i = 0; i < 3; ++i)
    inverted[i] = l[i] > kPseudoInverseFloor * l.maxCoeff() ? 1.0 / l[i] : 0.0;
  return eigen.eigenvectors() * inverted.asDiagonal() * eigen.eigenvectors().transpose();
}

TEST(PointBlockInverse, TheAdjugateAnswersOnlyWhenEveryEigenvalueIsAboveTheFloor) {
  std::mt19937_64 random(7);
  int answered = 0;
  for (int n = 0; n < 20000; ++n) {
    const Block block = randomBlock(random);
    Mat3 inverse;
    const bool well = invertWellConditioned(block.k, inverse);
    if (well) {
      ++answered;
      ASSERT_GT(block.smallestRatio(), kPseudoInverseFloor) << "case " << n;
      EXPECT_LT((inverse * block.k - Mat3::Identity()).cwiseAbs().maxCoeff(), 1e-6) << "case " << n;
    }
    // det >= 1e-4 and t <= 3 when every ratio is at least 1e-2: det / t^3 >= 3.7e-6.
    if (block.smallestRatio() >= 1e-2) EXPECT_TRUE(well) << "case " << n;
  }
  EXPECT_GT(answered, 20000 / 10);
}

TEST(PointBlockInverse, ThreePointsGiveWhatTheEigenvaluesGive) {
  std::mt19937_64 random(11);
  for (int n = 0; n < 20000; ++n) {
    const Block block = randomBlock(random);
    if (block.nearTheFloor()) continue;
    const Mat3 expected = byEigenvalues(block.k);
    const Mat3 got = pseudoInverse(block.k);
    // The closed-form eigenvalues carry an absolute error of about 1e-11 l_max: 1e-6 of the
    // smallest kept one.
    ASSERT_LT((got - expected).cwiseAbs().maxCoeff(), 1e-5 * expected.cwiseAbs().maxCoeff())
        << "case " << n << ", l_min / l_max " << block.smallestRatio();
  }
}

TEST(PointBlockInverse, AFacesFourPointsGiveTheMoorePenroseInverse) {
  // Four corners of a unit face on a resting unit cube (inverse mass 1, inverse inertia 6):
  // K_ij = 1 + 6 (r_i x n).(r_j x n), rank 3.
  const Vec3 n = Vec3::UnitZ();
  const Vec3 corners[4] = {
      {0.5, 0.5, -0.5}, {-0.5, 0.5, -0.5}, {-0.5, -0.5, -0.5}, {0.5, -0.5, -0.5}};
  SmallBlock k(4, 4);
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) k(i, j) = 1.0 + 6.0 * corners[i].cross(n).dot(corners[j].cross(n));
  }
  const SmallBlock plus = pseudoInverse(k);
  EXPECT_LT((k * plus * k - k).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT((plus * k * plus - plus).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT((k * plus - (k * plus).transpose()).cwiseAbs().maxCoeff(), 1e-12);
  // Equal closing speeds get equal shares: a quarter of the block's push each.
  const Eigen::Vector4d share = plus * Eigen::Vector4d::Ones();
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(share[i], 0.25, 1e-12);
}

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
