#include "mass_aggregate_sim/engine/implicit_euler.h"

#include <algorithm>
#include <cmath>

namespace mass_aggregate_sim {
namespace engine {
namespace {

using Mat3 = Eigen::Matrix3d;
constexpr Real kMinLength = 1e-12;

// dF_a/dx_a of a spring F_a = -k (l - L) n, d = x_a - x_b, n = d / l:
//   -k (n n^T + (1 - L/l) (I - n n^T)),
// with the transverse factor clamped at 0 (a compressed spring's transverse term would make the
// system indefinite). Also D = dF_a/dv_a = -c n n^T for the dashpot.
void springJacobians(const Vec3& d, const Real stiffness, const Real rest_length,
                     const Real damping, const bool pull_only, Mat3& k, Mat3& dv) {
  const Real length = d.norm();
  if (length < kMinLength || (pull_only && length <= rest_length)) {
    k.setZero();
    dv.setZero();
    return;
  }
  const Vec3 n = d / length;
  const Mat3 nn = n * n.transpose();
  const Real transverse = std::max(Real{0.0}, 1.0 - rest_length / length);
  k = -stiffness * (nn + transverse * (Mat3::Identity() - nn));
  dv = -damping * nn;
}

}  // namespace

void ImplicitEulerSolver::addBlock(const std::size_t row, const std::size_t col,
                                   const Mat3& block) {
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) {
      if (block(r, c) != 0.0) {
        triplets_.emplace_back(static_cast<int>(3 * row + r), static_cast<int>(3 * col + c),
                               block(r, c));
      }
    }
  }
}

// The matrix gets -h D - h^2 K; rows and columns of immovable particles are left out (their dv is
// zero), which is also why K v needs no terms from them (their v is zero).
void ImplicitEulerSolver::addSingle(const std::size_t a, const Mat3& k, const Mat3& d,
                                    const Eigen::Ref<const Vec3Array>& v, const Real h) {
  if (movable_[a] == 0.0) return;
  addBlock(a, a, -h * d - h * h * k);
  stiffness_times_v_.col(a) += k * v.col(a);
}

void ImplicitEulerSolver::addPair(const std::size_t a, const std::size_t b, const Mat3& k,
                                  const Mat3& d, const Eigen::Ref<const Vec3Array>& v,
                                  const Real h) {
  const Mat3 block = -h * d - h * h * k;
  const Vec3 kv = k * (v.col(a) - v.col(b));
  const bool move_a = movable_[a] != 0.0;
  const bool move_b = movable_[b] != 0.0;
  if (move_a) {
    addBlock(a, a, block);
    stiffness_times_v_.col(a) += kv;
  }
  if (move_b) {
    addBlock(b, b, block);
    stiffness_times_v_.col(b) -= kv;
  }
  if (move_a && move_b) {
    addBlock(a, b, -block);
    addBlock(b, a, -block);
  }
}

bool ImplicitEulerSolver::solve(const ForceGenerators& generators, const ParticleStore& particles,
                                const Eigen::Ref<const Vec3Array>& acceleration,
                                const Real gravity_magnitude, const Real h,
                                Eigen::Ref<Vec3Array> dv) {
  const std::size_t n = particles.size();
  const auto x = particles.positions();
  const auto v = particles.velocities();
  const auto inverse_mass = particles.inverseMasses();
  const auto index = [&particles](const ParticleId id) {
    return particles.denseIndexUnchecked(id);
  };
  movable_ = particles.mobility();
  stiffness_times_v_.setZero(3, static_cast<Eigen::Index>(n));
  triplets_.clear();
  triplets_.reserve(3 * n + 18 * generators.size());

  for (std::size_t i = 0; i < n; ++i) {
    const Real mass = inverse_mass[i] > 0.0 ? 1.0 / inverse_mass[i] : 1.0;
    addBlock(i, i, mass * Mat3::Identity());
  }

  Mat3 k;
  Mat3 d;
  for (const Spring& s : generators.springs) {
    const std::size_t a = index(s.a);
    const std::size_t b = index(s.b);
    springJacobians(x.col(a) - x.col(b), s.stiffness, s.rest_length, s.damping, false, k, d);
    addPair(a, b, k, d, v, h);
  }
  for (const Bungee& s : generators.bungees) {
    const std::size_t a = index(s.a);
    const std::size_t b = index(s.b);
    springJacobians(x.col(a) - x.col(b), s.stiffness, s.rest_length, s.damping, true, k, d);
    addPair(a, b, k, d, v, h);
  }
  for (const AnchoredSpring& s : generators.anchored_springs) {
    const std::size_t a = index(s.particle);
    springJacobians(x.col(a) - s.anchor, s.stiffness, s.rest_length, s.damping, false, k, d);
    addSingle(a, k, d, v, h);
  }
  for (const AnchoredBungee& s : generators.anchored_bungees) {
    const std::size_t a = index(s.particle);
    springJacobians(x.col(a) - s.anchor, s.stiffness, s.rest_length, s.damping, true, k, d);
    addSingle(a, k, d, v, h);
  }
  for (const Drag& drag : generators.drags) {
    const std::size_t a = index(drag.particle);
    const Vec3 va = v.col(a);
    const Real speed = va.norm();
    // d/dv of -(k1 + k2 |v|) v = -(k1 + k2 |v|) I - k2 v v^T / |v|
    d = -(drag.k1 + drag.k2 * speed) * Mat3::Identity();
    if (speed > 0.0) d -= drag.k2 * va * va.transpose() / speed;
    addSingle(a, Mat3::Zero(), d, v, h);
  }
  for (const Buoyancy& b : generators.buoyancies) {
    const std::size_t a = index(b.particle);
    const Real height = b.up.dot(x.col(a)) - b.surface_height;
    if (std::abs(height) >= b.max_depth) continue;
    // In the partly submerged band the force falls linearly with height.
    k = -(b.liquid_density * b.volume * gravity_magnitude / (2.0 * b.max_depth)) * b.up *
        b.up.transpose();
    addSingle(a, k, Mat3::Zero(), v, h);
  }

  const Eigen::Index size = static_cast<Eigen::Index>(3 * n);
  matrix_.resize(size, size);
  matrix_.setFromTriplets(triplets_.begin(), triplets_.end());
  solver_.compute(matrix_);
  if (solver_.info() != Eigen::Success) return false;

  rhs_.resize(size);
  for (std::size_t i = 0; i < n; ++i) {
    if (inverse_mass[i] > 0.0) {
      // h (f0 + h K v), f0 = m a
      rhs_.segment<3>(static_cast<Eigen::Index>(3 * i)) =
          h * (acceleration.col(i) / inverse_mass[i] + h * stiffness_times_v_.col(i));
    } else {
      rhs_.segment<3>(static_cast<Eigen::Index>(3 * i)).setZero();
    }
  }
  const Eigen::VectorXd solution = solver_.solve(rhs_);
  if (solver_.info() != Eigen::Success || !solution.allFinite()) return false;
  dv = Eigen::Map<const Vec3Array>(solution.data(), 3, static_cast<Eigen::Index>(n));
  return true;
}

}  // namespace engine
}  // namespace mass_aggregate_sim
