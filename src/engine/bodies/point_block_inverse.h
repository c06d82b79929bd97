#pragma once
// Pseudo-inverses of the blocks that couple a manifold's points through the bodies,
// K_ij = J_i M^-1 J_j^T: symmetric, positive semi-definite, at most four points square.
//
// Eigenvalues below kPseudoInverseFloor times the largest count as zero. A face's four coplanar
// points make K singular (rank 3: push, and turn about two axes), and closing speeds that differ
// by rounding are then not quite in its range: an inverse would answer with huge opposite
// impulses on alternate corners; the pseudo-inverse gives the least-squares, least-norm share.

#include <Eigen/Core>

#include "engine/collision/narrowphase/manifold.h"
#include "mass_aggregate_sim/engine/core/transform.h"

namespace mass_aggregate_sim {
namespace engine {

// A square block of at most four points, held without the heap.
using SmallBlock = Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic, 0, Manifold::kMaxPoints,
                                 Manifold::kMaxPoints>;

constexpr Real kPseudoInverseFloor = 1e-6;

// K^-1 when every eigenvalue of K is certainly above the floor (then K^+ = K^-1), by the adjugate:
// with trace t >= l_max and det = l_1 l_2 l_3 <= l_min t^2, det > floor t^3 gives
// l_min > floor l_max. False when that is not certain (K may still be well conditioned).
bool invertWellConditioned(const Mat3& k, Mat3& inverse);

// K^+ of a 3 x 3 block: the adjugate when invertWellConditioned answers, else the eigenvalues.
Mat3 pseudoInverse(const Mat3& k);
// K^+ of a block of one to four points.
SmallBlock pseudoInverse(const SmallBlock& k);

}  // namespace engine
}  // namespace mass_aggregate_sim
