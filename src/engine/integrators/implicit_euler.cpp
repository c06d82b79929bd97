// Implicit Euler: the linearised backward Euler solve (ImplicitEulerSolver), the particle damping
// v' = ln(d) v inside it, then v' = v + dv and x' = x + v' h. First order; unconditionally stable,
// and damps.
#include "engine/integrators/implicit_euler.h"

#include <cmath>

#include "engine/integrators/integrators.h"
#include "engine/world/step_context.h"

namespace mass_aggregate_sim {
namespace engine {

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

void ImplicitEulerSolver::addSingle(const std::size_t a, const Mat3& k, const Mat3& d) {
  if (movable_[a] == 0.0) return;
  addBlock(a, a, -h_ * d - h_ * h_ * k);
  stiffness_times_v_.col(a) += k * v_->col(a);
}

void ImplicitEulerSolver::addPair(const std::size_t a, const std::size_t b, const Mat3& k,
                                  const Mat3& d) {
  const Mat3 block = -h_ * d - h_ * h_ * k;
  const Vec3 kv = k * (v_->col(a) - v_->col(b));
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
  const auto inverse_mass = particles.inverseMasses();
  particles_ = &particles;
  x_.emplace(particles.positions());
  v_.emplace(particles.velocities());
  gravity_magnitude_ = gravity_magnitude;
  h_ = h;
  movable_ = particles.mobility();
  // Particle damping is the force m ln(d) v, so D gains m ln(d) I on the diagonal. A particle
  // with d = 0 is held still over the step (the limit of ln(d) -> -inf: v' = 0, x' = x).
  const auto damping = particles.dampings();
  damping_rate_.resize(static_cast<Eigen::Index>(n));
  for (std::size_t i = 0; i < n; ++i) {
    damping_rate_[i] = damping[i] > 0.0 ? std::log(damping[i]) : 0.0;
    if (damping[i] == 0.0) movable_[i] = 0.0;
  }
  stiffness_times_v_.setZero(3, static_cast<Eigen::Index>(n));
  triplets_.clear();
  triplets_.reserve(3 * n + 18 * generators.size());

  for (std::size_t i = 0; i < n; ++i) {
    const Real mass = inverse_mass[i] > 0.0 ? 1.0 / inverse_mass[i] : 1.0;
    // M - h D for the damping: m (1 - h ln d)
    addBlock(i, i, mass * (1.0 - h * damping_rate_[i]) * Mat3::Identity());
  }
  generators.forEach([&](const auto& kind) {
    using Kind = typename std::decay_t<decltype(kind)>::value_type;
    ForceKind<Kind>::linearise(kind, *this);
  });

  const Eigen::Index size = static_cast<Eigen::Index>(3 * n);
  matrix_.resize(size, size);
  matrix_.setFromTriplets(triplets_.begin(), triplets_.end());
  solver_.compute(matrix_);
  x_.reset();
  v_.reset();
  if (solver_.info() != Eigen::Success) return false;

  rhs_.resize(size);
  const auto v = particles.velocities();
  for (std::size_t i = 0; i < n; ++i) {
    if (movable_[i] != 0.0) {
      // h (f0 + h K v), f0 = m a + m ln(d) v
      const Real mass = 1.0 / inverse_mass[i];
      rhs_.segment<3>(static_cast<Eigen::Index>(3 * i)) =
          h * (mass * (acceleration.col(i) + damping_rate_[i] * v.col(i)) +
               h * stiffness_times_v_.col(i));
    } else {
      rhs_.segment<3>(static_cast<Eigen::Index>(3 * i)).setZero();
    }
  }
  const Eigen::VectorXd solution = solver_.solve(rhs_);
  if (solver_.info() != Eigen::Success || !solution.allFinite()) return false;
  dv = Eigen::Map<const Vec3Array>(solution.data(), 3, static_cast<Eigen::Index>(n));
  return true;
}

void integrateImplicitEuler(StepContext& ctx) {
  ParticleStore& particles = ctx.particles;
  auto x = particles.positions();
  auto v = particles.velocities();
  Vec3Array& a = ctx.integration.acceleration;
  Vec3Array& dv = ctx.caches.scratch_v;
  const Real h = ctx.h;
  ctx.accelerations(x, v, a);
  dv.resize(3, x.cols());
  if (!ctx.caches.implicit.solve(ctx.generators, particles, a, ctx.config.gravity.norm(), h, dv)) {
    // Reported, then stepped explicitly so the world still advances.
    ctx.reportDivergence(ParticleId{}, "implicit Euler: sparse factorisation failed");
    dv = h * a;
  }
  const auto damping = particles.dampings();
  for (std::size_t i = 0; i < particles.size(); ++i) {
    // v' = v + dv (0 when d = 0),  x' = x + v' h
    v.col(i) = damping[i] > 0.0 ? Vec3(v.col(i) + dv.col(i)) : Vec3::Zero();
    x.col(i) += v.col(i) * h;
  }
}

}  // namespace engine
}  // namespace mass_aggregate_sim
