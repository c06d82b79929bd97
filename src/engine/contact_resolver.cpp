#include "mass_aggregate_sim/engine/contact_resolver.h"

#include <algorithm>
#include <cmath>

namespace mass_aggregate_sim {
namespace engine {
namespace {

constexpr Real kMinLinkLength = 1e-12;

bool hasB(const Contact& c) { return c.b != kNoParticle; }

}  // namespace

void ContactResolver::touch(const std::uint32_t i) {
  if (touched_flag_[i]) return;
  touched_flag_[i] = 1;
  touched_.push_back(i);
}

bool ContactResolver::linkState(const Contact& c, const Vec3Map& x, Vec3& normal,
                                Real& error) const {
  const Vec3 other = hasB(c) ? Vec3(x.col(c.b)) : c.anchor;
  const Vec3 d = other - x.col(c.a);
  const Real length = d.norm();
  if (length < kMinLinkLength) return false;
  normal = d / length;
  error = length - c.length;
  return true;
}

Real ContactResolver::lastImpulse(const std::uint64_t key) const {
  const auto it =
      std::lower_bound(warm_impulses_.begin(), warm_impulses_.end(), key,
                       [](const WarmStart& entry, const std::uint64_t k) { return entry.key < k; });
  return it != warm_impulses_.end() && it->key == key ? it->normal : 0.0;
}

void ContactResolver::resolve(std::vector<Contact>& contacts, Vec3Map x, Vec3Map v,
                              const ConstScalarMap& inverse_mass,
                              const Eigen::Ref<const Vec3Array>& acceleration, const Real h,
                              const CollisionSettings& settings, const Real position_weight,
                              ContactStats& stats) {
  for (const std::uint32_t i : touched_) {
    touched_flag_[i] = 0;
    displacement_.col(i).setZero();
  }
  touched_.clear();
  last_substep_ = h;
  follow_scale_ = h * position_weight;
  const Eigen::Index n = x.cols();
  if (displacement_.cols() != n) {
    displacement_.setZero(3, n);
    touched_flag_.assign(static_cast<std::size_t>(n), 0);
  }

  const std::size_t count = contacts.size();
  inverse_mass_sum_.resize(count);
  built_velocity_.resize(count);
  resting_.resize(count);
  velocity_active_.resize(count);
  for (std::size_t k = 0; k < count; ++k) {
    Contact& c = contacts[k];
    const Real wa = inverse_mass[c.a];
    const Real wb = hasB(c) ? inverse_mass[c.b] : 0.0;
    inverse_mass_sum_[k] = wa + wb;
    Vec3 relative_acceleration = wa > 0.0 ? Vec3(acceleration.col(c.a)) : Vec3::Zero();
    Real acceleration_bound = wa > 0.0 ? relative_acceleration.norm() : 0.0;
    if (hasB(c) && wb > 0.0) {
      relative_acceleration -= acceleration.col(c.b);
      acceleration_bound += acceleration.col(c.b).norm();
    }
    if (c.kind != ContactKind::kContact) {
      Vec3 normal;
      Real error;
      if (linkState(c, x, normal, error)) {
        c.normal = normal;
        c.penetration = error;
      } else {
        inverse_mass_sum_[k] = 0.0;  // coincident ends: no direction to act along
      }
    }
    // Closing velocity the forces built over the substep, counted only for the fraction of it the
    // contact already existed: the overlap d, reached at closing speed |v_sep|, took d / |v_sep|.
    const Real v_sep =
        (Vec3(v.col(c.a)) - (hasB(c) ? Vec3(v.col(c.b)) : Vec3::Zero())).dot(c.normal);
    const Real built = std::min(Real{0.0}, relative_acceleration.dot(c.normal) * h);
    Real in_contact = 1.0;
    if (v_sep < 0.0) in_contact = std::clamp(c.penetration / (-v_sep * h), Real{0.0}, Real{1.0});
    built_velocity_[k] = built * in_contact;
    // Resting: what is left of the closing speed after removing all the forces built over the
    // substep is below what they can build in two more (explicit Euler moves with the velocity of
    // the step before, so one substep of slack is not enough). Then the target is 0, no bounce.
    resting_[k] = v_sep - built > -2.0 * acceleration_bound * h;
    // A gap (a contact not yet touching, a cable not yet taut) matters only for slow approaches:
    // it then keeps them from closing faster than the gap allows, so a resting contact or a loaded
    // cable that flickers open does not fall free for a substep and come back with a jolt. A fast
    // approach is let through, to bounce properly in the next substep.
    velocity_active_[k] = inverse_mass_sum_[k] > 0.0 &&
                          !(c.kind != ContactKind::kRod && c.penetration < 0.0 && !resting_[k]);
  }

  stats.velocity_iterations = resolveVelocities(contacts, v, inverse_mass, h, settings);
  if (follow_scale_ > 0.0) followRestingImpulses(contacts, x, inverse_mass, follow_scale_);
  stats.position_iterations = resolvePositions(contacts, x, inverse_mass, settings);
  stats.iterations = stats.velocity_iterations + stats.position_iterations;

  // What is left: the largest overlap beyond zero and the largest closing speed.
  stats.max_penetration = 0.0;
  stats.max_closing_velocity = 0.0;
  for (std::size_t k = 0; k < count; ++k) {
    const Contact& c = contacts[k];
    if (inverse_mass_sum_[k] <= 0.0) continue;
    Real violation = 0.0;
    Vec3 normal = c.normal;
    if (c.kind == ContactKind::kContact) {
      violation = c.penetration - (Vec3(displacement_.col(c.a)) -
                                   (hasB(c) ? Vec3(displacement_.col(c.b)) : Vec3::Zero()))
                                      .dot(c.normal);
    } else {
      Real error;
      if (!linkState(c, x, normal, error)) continue;
      violation = c.kind == ContactKind::kRod ? std::abs(error) : error;
    }
    stats.max_penetration = std::max(stats.max_penetration, violation);
    if (!velocity_active_[k]) continue;
    const Real v_sep =
        (Vec3(v.col(c.a)) - (hasB(c) ? Vec3(v.col(c.b)) : Vec3::Zero())).dot(c.normal);
    // Beyond what the constraint allows: closing at all, or faster than a gap can absorb.
    const Real allowed = c.kind != ContactKind::kRod ? std::min(Real{0.0}, c.penetration / h) : 0.0;
    const Real closing = c.kind == ContactKind::kRod ? std::abs(v_sep) : allowed - v_sep;
    stats.max_closing_velocity = std::max(stats.max_closing_velocity, closing);
  }
}

int ContactResolver::resolveVelocities(std::vector<Contact>& contacts, Vec3Map& v,
                                       const ConstScalarMap& inverse_mass, const Real h,
                                       const CollisionSettings& settings) {
  const std::size_t count = contacts.size();
  total_.assign(count, 0.0);
  target_.assign(count, 0.0);
  const auto separating = [&](const Contact& c) {
    return (Vec3(v.col(c.a)) - (hasB(c) ? Vec3(v.col(c.b)) : Vec3::Zero())).dot(c.normal);
  };
  // Contacts mostly come in the order of their keys, so each lookup starts where the last one
  // ended: everything before `hint` is below the last key, hence below any key not smaller.
  const auto key_below = [](const WarmStart& entry, const std::uint64_t key) {
    return entry.key < key;
  };
  friction_total_.assign(count, Vec3::Zero());
  auto hint = warm_impulses_.begin();
  std::uint64_t hint_key = 0;
  for (std::size_t k = 0; k < count; ++k) {
    const Contact& c = contacts[k];
    if (!velocity_active_[k]) continue;
    if (c.key < hint_key) hint = warm_impulses_.begin();
    auto it = hint;
    for (int probe = 0; probe < 4 && it != warm_impulses_.end() && it->key < c.key; ++probe) {
      ++it;
    }
    if (it != warm_impulses_.end() && it->key < c.key) {
      it = std::lower_bound(it, warm_impulses_.end(), c.key, key_below);
    }
    hint = it;
    hint_key = c.key;
    const bool found = it != warm_impulses_.end() && it->key == c.key;
    const Real previous = found ? it->normal : 0.0;
    // Targets are fixed from the velocities before any impulse (the total impulse is what the
    // passes converge, so a bounce must not be re-evaluated from a half-solved state). A contact
    // or cable that already pushed or pulled in the last substep is holding, not hitting.
    if (c.kind == ContactKind::kContact && resting_[k] && follow_scale_ > 0.0) {
      // A resting contact moves by beta h (v''_sep - v'_sep) after this phase, which leaves the
      // overlap p - beta h (v''_sep - v'_sep): aim at touching when that is within reach, never
      // at pushing apart (overlap beyond the slop is the position passes' work).
      target_[k] = std::min(Real{0.0}, separating(c) + c.penetration / follow_scale_);
    } else if (c.kind != ContactKind::kRod && c.penetration < 0.0) {
      // A gap g may close at up to g / h within the substep, no faster.
      target_[k] = c.penetration / h;
    } else if (c.kind != ContactKind::kRod && !resting_[k] && previous <= 0.0) {
      target_[k] = -c.restitution * std::min(Real{0.0}, separating(c) - built_velocity_[k]);
    }
    total_[k] = c.kind == ContactKind::kRod ? previous : std::max(Real{0.0}, previous);
    if (found && c.kind == ContactKind::kContact && c.friction > 0.0) {
      // The last friction impulse, in the current tangent plane and within mu j_n.
      Vec3 friction = it->friction - it->friction.dot(c.normal) * c.normal;
      const Real limit = c.friction * total_[k];
      const Real magnitude = friction.norm();
      if (magnitude > limit) friction *= limit / magnitude;
      friction_total_[k] = friction;
    }
  }
  // Warm start: each constraint begins with the impulse it ended the last substep with.
  for (std::size_t k = 0; k < count; ++k) {
    const Real j = total_[k];
    if (j == 0.0) continue;
    const Contact& c = contacts[k];
    const Vec3 impulse = j * c.normal + friction_total_[k];
    v.col(c.a) += inverse_mass[c.a] * impulse;
    touch(c.a);
    if (hasB(c)) {
      v.col(c.b) -= inverse_mass[c.b] * impulse;
      touch(c.b);
    }
  }

  int passes = 0;
  while (passes < settings.max_iterations) {
    ++passes;
    Real largest_change = 0.0;
    // Alternate the sweep direction (symmetric Gauss-Seidel): chains converge from both ends.
    const bool backward = passes % 2 == 0;
    for (std::size_t step = 0; step < count; ++step) {
      const std::size_t k = backward ? count - 1 - step : step;
      if (!velocity_active_[k]) continue;
      const Real w_sum = inverse_mass_sum_[k];
      const Contact& c = contacts[k];
      const bool b = hasB(c);
      const Real wa = inverse_mass[c.a];
      const Real wb = b ? inverse_mass[c.b] : 0.0;
      // j = (v_target - v_sep) / (w_a + w_b), accumulated: contacts and cables never pull
      // together / push apart in total, rods act either way.
      Real total = total_[k] + (target_[k] - separating(c)) / w_sum;
      if (c.kind != ContactKind::kRod) total = std::max(Real{0.0}, total);
      const Real j = total - total_[k];
      total_[k] = total;
      if (j != 0.0) {
        v.col(c.a) += (j * wa) * c.normal;
        if (b) v.col(c.b) -= (j * wb) * c.normal;
        if (wa > 0.0) touch(c.a);
        if (b && wb > 0.0) touch(c.b);
        largest_change = std::max(largest_change, std::abs(j * w_sum));
      }
      if (c.kind == ContactKind::kContact && c.friction > 0.0) {
        // Coulomb: the total tangential impulse removes slip but stays within mu j_n.
        const Vec3 relative = Vec3(v.col(c.a)) - (b ? Vec3(v.col(c.b)) : Vec3::Zero());
        const Vec3 slip = relative - relative.dot(c.normal) * c.normal;
        Vec3 friction = friction_total_[k] - slip / w_sum;
        const Real limit = c.friction * total_[k];
        const Real magnitude = friction.norm();
        if (magnitude > limit) friction *= limit / magnitude;
        const Vec3 change = friction - friction_total_[k];
        friction_total_[k] = friction;
        v.col(c.a) += wa * change;
        if (b) v.col(c.b) -= wb * change;
        largest_change = std::max(largest_change, change.norm() * w_sum);
      }
    }
    if (largest_change <= settings.velocity_tolerance) break;
  }
  next_warm_impulses_.clear();
  for (std::size_t k = 0; k < count; ++k) {
    if (velocity_active_[k] && total_[k] != 0.0) {
      next_warm_impulses_.push_back({contacts[k].key, total_[k], friction_total_[k]});
    }
  }
  const auto by_key = [](const WarmStart& x, const WarmStart& y) { return x.key < y.key; };
  if (!std::is_sorted(next_warm_impulses_.begin(), next_warm_impulses_.end(), by_key)) {
    std::sort(next_warm_impulses_.begin(), next_warm_impulses_.end(), by_key);
  }
  warm_impulses_.swap(next_warm_impulses_);
  return passes;
}

void ContactResolver::followRestingImpulses(const std::vector<Contact>& contacts, Vec3Map& x,
                                            const ConstScalarMap& inverse_mass, const Real scale) {
  const std::size_t count = contacts.size();
  for (std::size_t k = 0; k < count; ++k) {
    const Contact& c = contacts[k];
    if (c.kind != ContactKind::kContact || !resting_[k] || !velocity_active_[k]) continue;
    const Vec3 impulse = total_[k] * c.normal + friction_total_[k];
    if (impulse.isZero(0.0)) continue;
    // dx = beta h w J: the move the integrator would have made had the impulse been in the step.
    const Real wa = inverse_mass[c.a];
    if (wa > 0.0) {
      const Vec3 move_a = (scale * wa) * impulse;
      x.col(c.a) += move_a;
      displacement_.col(c.a) += move_a;
      touch(c.a);
    }
    if (hasB(c)) {
      const Real wb = inverse_mass[c.b];
      if (wb > 0.0) {
        const Vec3 move_b = (-scale * wb) * impulse;
        x.col(c.b) += move_b;
        displacement_.col(c.b) += move_b;
        touch(c.b);
      }
    }
  }
}

int ContactResolver::resolvePositions(std::vector<Contact>& contacts, Vec3Map& x,
                                      const ConstScalarMap& inverse_mass,
                                      const CollisionSettings& settings) {
  const std::size_t count = contacts.size();
  const Real slop = settings.penetration_slop;
  int passes = 0;
  while (passes < settings.max_iterations) {
    ++passes;
    bool corrected = false;
    const bool backward = passes % 2 == 0;
    for (std::size_t step = 0; step < count; ++step) {
      const std::size_t k = backward ? count - 1 - step : step;
      const Real w_sum = inverse_mass_sum_[k];
      if (w_sum <= 0.0) continue;
      const Contact& c = contacts[k];
      const bool b = hasB(c);
      Vec3 normal = c.normal;
      Real correction = 0.0;
      if (c.kind == ContactKind::kContact) {
        const Real depth = c.penetration - (Vec3(displacement_.col(c.a)) -
                                            (b ? Vec3(displacement_.col(c.b)) : Vec3::Zero()))
                                               .dot(normal);
        if (depth <= slop) continue;
        correction = depth - 0.5 * slop;
      } else {
        Real error;
        if (!linkState(c, x, normal, error)) continue;
        const Real allowed = settings.rod_tolerance * c.length;
        if (c.kind == ContactKind::kCable ? error <= allowed : std::abs(error) <= allowed) continue;
        correction = error;
      }
      // dp_a = w_a / (w_a + w_b) d n,  dp_b = -w_b / (w_a + w_b) d n
      const Real wa = inverse_mass[c.a];
      const Vec3 move_a = (correction * wa / w_sum) * normal;
      x.col(c.a) += move_a;
      displacement_.col(c.a) += move_a;
      if (wa > 0.0) touch(c.a);
      if (b) {
        const Real wb = inverse_mass[c.b];
        const Vec3 move_b = (-correction * wb / w_sum) * normal;
        x.col(c.b) += move_b;
        displacement_.col(c.b) += move_b;
        if (wb > 0.0) touch(c.b);
      }
      corrected = true;
    }
    if (!corrected) break;
  }
  return passes;
}

}  // namespace engine
}  // namespace mass_aggregate_sim
