// The six integrators of World, one function each. Every one ends with damping v *= d^h, using the
// factors cached by refreshDampingFactors().
#include <Eigen/Core>

#include "mass_aggregate_sim/engine/force_evaluation.h"
#include "mass_aggregate_sim/engine/implicit_euler.h"
#include "mass_aggregate_sim/engine/semi_implicit_pass.h"
#include "mass_aggregate_sim/engine/world.h"

namespace mass_aggregate_sim {
namespace engine {

void World::integrateExplicitEuler(const Real h) {
  auto x = particles_.positions();
  auto v = particles_.velocities();
  computeAccelerations(x, v, h, acceleration_);
  for (std::size_t i = 0; i < particles_.size(); ++i) {
    // x' = x + v h,  v' = (v + a h) d^h
    x.col(i) += v.col(i) * h;
    v.col(i) = (v.col(i) + acceleration_.col(i) * h) * damping_factor_[i];
  }
}

void World::integrateSemiImplicitEuler(const Real h) {
  auto x = particles_.positions();
  auto v = particles_.velocities();
  const bool has_forces = !generators_.empty() || has_external_force_;
  const bool ahead =
      forces_ahead_valid_ && !has_external_force_ && forces_ahead_.cols() == acceleration_.cols();
  forces_ahead_valid_ = false;
  if (has_forces && ahead) {
    acceleration_.swap(forces_ahead_);  // evaluated at this state by the energy guard
  } else if (has_forces) {
    if (has_external_force_) {
      acceleration_ = particles_.forces();
    } else {
      acceleration_.setZero();  // the external forces are all zero
    }
    accumulateGeneratorForces(generators_, particles_, x, v, config_.gravity.norm(), h,
                              acceleration_, denseSprings());
  }
  const Real g[3] = {config_.gravity.x(), config_.gravity.y(), config_.gravity.z()};
  // The energy guard reads the state the step ends in: this pass sums it unless contacts move
  // particles afterwards.
  const bool energies = energyGuardApplies() && !contactsActive() &&
                        mass_.size() == static_cast<Eigen::Index>(particles_.size());
  SemiImplicitInputs in;
  in.count = particles_.size();
  in.h = h;
  in.gravity = g;
  in.inverse_mass = particles_.inverseMasses().data();
  in.mobility = particles_.mobility().data();
  in.own_acceleration = particles_.accelerations().data();
  in.damping_factor = damping_factor_.data();
  in.mass = mass_.data();
  EnergyAccumulator sums;
  semiImplicitEulerPass(in, has_forces, acceleration_.data(), x.data(), v.data(),
                        energies ? &sums : nullptr);
  pass_energies_valid_ = energies;
  if (energies) pass_energies_ = sums.sums(g);
}

void World::integratePositionVerlet(const Real h) {
  auto x = particles_.positions();
  auto v = particles_.velocities();
  auto previous = particles_.previousPositions();
  computeAccelerations(x, v, h, acceleration_);
  if (verlet_history_h_ != h) {
    // A consistent start from the Taylor expansion: x_prev = x - v h + a h^2 / 2.
    previous = x - v * h + 0.5 * h * h * acceleration_;
  }
  for (std::size_t i = 0; i < particles_.size(); ++i) {
    const Vec3 current = x.col(i);
    // x' = x + (x - x_prev) d^h + a h^2   (= 2x - x_prev + a h^2 undamped)
    const Vec3 next =
        current + (current - previous.col(i)) * damping_factor_[i] + acceleration_.col(i) * (h * h);
    // (x' - x)/h is the velocity half a step back; adding a h/2 makes it second order at x'.
    v.col(i) = (next - current) / h + 0.5 * h * acceleration_.col(i);
    previous.col(i) = current;
    x.col(i) = next;
  }
  verlet_history_h_ = h;
}

void World::integrateVelocityVerlet(const Real h) {
  auto x = particles_.positions();
  auto v = particles_.velocities();
  if (!acceleration_valid_) computeAccelerations(x, v, h, acceleration_);
  Vec3Array& next_acceleration = stage_a_[0];
  next_acceleration.resize(3, x.cols());
  // x' = x + v h + a h^2/2; forces at x' see the predicted velocity v + a h.
  x += v * h + (0.5 * h * h) * acceleration_;
  scratch_v_ = v + h * acceleration_;
  computeAccelerations(x, scratch_v_, h, next_acceleration);
  for (std::size_t i = 0; i < particles_.size(); ++i) {
    // v' = (v + (a + a') h/2) d^h
    v.col(i) = (v.col(i) + 0.5 * h * (acceleration_.col(i) + next_acceleration.col(i))) *
               damping_factor_[i];
  }
  acceleration_.swap(next_acceleration);
  acceleration_valid_ = true;
}

void World::integrateRk4(const Real h) {
  auto x = particles_.positions();
  auto v = particles_.velocities();
  Vec3Array& stage_acceleration = stage_a_[0];
  Vec3Array& velocity_sum = stage_a_[1];
  Vec3Array& acceleration_sum = acceleration_;
  stage_acceleration.resize(3, x.cols());

  // k1 at (x, v)
  computeAccelerations(x, v, h, stage_acceleration);
  velocity_sum = v;
  acceleration_sum = stage_acceleration;
  // k2 at (x + v h/2, v + a1 h/2)
  scratch_x_ = x + (0.5 * h) * v;
  scratch_v_ = v + (0.5 * h) * stage_acceleration;
  computeAccelerations(scratch_x_, scratch_v_, h, stage_acceleration);
  velocity_sum += 2.0 * scratch_v_;
  acceleration_sum += 2.0 * stage_acceleration;
  // k3 at (x + v2 h/2, v + a2 h/2)
  scratch_x_ = x + (0.5 * h) * scratch_v_;
  scratch_v_ = v + (0.5 * h) * stage_acceleration;
  computeAccelerations(scratch_x_, scratch_v_, h, stage_acceleration);
  velocity_sum += 2.0 * scratch_v_;
  acceleration_sum += 2.0 * stage_acceleration;
  // k4 at (x + v3 h, v + a3 h)
  scratch_x_ = x + h * scratch_v_;
  scratch_v_ = v + h * stage_acceleration;
  computeAccelerations(scratch_x_, scratch_v_, h, stage_acceleration);
  velocity_sum += scratch_v_;
  acceleration_sum += stage_acceleration;

  // x' = x + h/6 (v1 + 2 v2 + 2 v3 + v4),  v' = (v + h/6 (a1 + 2 a2 + 2 a3 + a4)) d^h
  x += (h / 6.0) * velocity_sum;
  for (std::size_t i = 0; i < particles_.size(); ++i) {
    v.col(i) = (v.col(i) + (h / 6.0) * acceleration_sum.col(i)) * damping_factor_[i];
  }
  acceleration_sum /= 6.0;
}

void World::integrateImplicitEuler(const Real h) {
  auto x = particles_.positions();
  auto v = particles_.velocities();
  computeAccelerations(x, v, h, acceleration_);
  scratch_v_.resize(3, x.cols());
  if (!implicit_solver_) implicit_solver_ = std::make_unique<ImplicitEulerSolver>();
  if (!implicit_solver_->solve(generators_, particles_, acceleration_, config_.gravity.norm(), h,
                               scratch_v_)) {
    // Reported, then stepped explicitly so the world still advances.
    last_divergence_ = DivergenceEvent{step_count_, time(), ParticleId{},
                                       "implicit Euler: sparse factorisation failed"};
    ++divergence_count_;
    scratch_v_ = h * acceleration_;
  }
  for (std::size_t i = 0; i < particles_.size(); ++i) {
    // v' = (v + dv) d^h,  x' = x + v' h
    v.col(i) = (v.col(i) + scratch_v_.col(i)) * damping_factor_[i];
    x.col(i) += v.col(i) * h;
  }
}

}  // namespace engine
}  // namespace mass_aggregate_sim
