#pragma once
// The contact response, written once over a lane type T: Real for one contact, simd::Real4 for
// four contacts in vector lanes. Both instances run the same operations in the same order, so each
// lane gets the bits the scalar instance gives, and ContactResolver's rows use the same pieces:
//   the resting test, the target separating velocity, the warm start, the accumulated impulse,
//   Coulomb friction, the follow of resting impulses and the position correction.
// Comparisons give Mask<T> (bool, or a lane mask); branches become selects where a lane type
// needs them, and are skipped only where no lane needs them.

#include <algorithm>
#include <cmath>
#include <limits>

#include "engine/core/simd.h"
#include "mass_aggregate_sim/engine/core/types.h"

namespace mass_aggregate_sim {
namespace engine {
namespace response {

template <typename T>
struct Lane;

template <>
struct Lane<Real> {
  using Mask = bool;
  static Real broadcast(const Real value) { return value; }
  static Real select(const bool mask, const Real if_set, const Real otherwise) {
    return mask ? if_set : otherwise;
  }
  static bool choose(const bool mask, const bool if_set, const bool otherwise) {
    return mask ? if_set : otherwise;
  }
  static bool any(const bool mask) { return mask; }
  static bool all(const bool mask) { return mask; }
  static bool both(const bool a, const bool b) { return a && b; }
  static bool either(const bool a, const bool b) { return a || b; }
  static bool negate(const bool a) { return !a; }
  static Real sqrt(const Real value) { return std::sqrt(value); }
};

template <>
struct Lane<simd::Real4> {
  using Mask = simd::Mask4;
  static simd::Real4 broadcast(const Real value) { return simd::broadcast(value); }
  static simd::Real4 select(const Mask mask, const simd::Real4 if_set,
                            const simd::Real4 otherwise) {
    return simd::select(mask, if_set, otherwise);
  }
  static Mask choose(const Mask mask, const Mask if_set, const Mask otherwise) {
    return (if_set & mask) | (otherwise & ~mask);
  }
  static bool any(const Mask mask) { return (mask[0] | mask[1] | mask[2] | mask[3]) != 0; }
  static bool all(const Mask mask) { return simd::allSet(mask); }
  static Mask both(const Mask a, const Mask b) { return a & b; }
  static Mask either(const Mask a, const Mask b) { return a | b; }
  static Mask negate(const Mask a) { return ~a; }
  static simd::Real4 sqrt(const simd::Real4 value) {
    return simd::Real4{std::sqrt(value[0]), std::sqrt(value[1]), std::sqrt(value[2]),
                       std::sqrt(value[3])};
  }
};

template <typename T>
using Mask = typename Lane<T>::Mask;

constexpr Real kInfinity = std::numeric_limits<Real>::infinity();

// A 3-vector of lanes.
template <typename T>
struct Vec {
  T c[3];
  T& operator[](const int k) { return c[k]; }
  const T& operator[](const int k) const { return c[k]; }
};

// Eigen's order for a 3-vector dot product: (a0 b0 + a1 b1) + a2 b2.
template <typename T>
inline T dot(const Vec<T>& a, const Vec<T>& b) {
  return (a[0] * b[0] + a[1] * b[1]) + a[2] * b[2];
}

// std::min(0, value) and std::max(0, value): (value < 0 ? value : 0) and (0 < value ? value : 0),
// so a NaN gives 0 as it does there.
template <typename T>
inline T minZero(const T value) {
  const T zero = Lane<T>::broadcast(0.0);
  return Lane<T>::select(value < zero, value, zero);
}
template <typename T>
inline T maxZero(const T value) {
  const T zero = Lane<T>::broadcast(0.0);
  return Lane<T>::select(zero < value, value, zero);
}

// Resting: what is left of the closing speed after removing all the forces built over the
// substep is below what they can build in two more (explicit Euler moves with the velocity of the
// step before, so one substep of slack is not enough): closing_less_built > -2 |a| h, with |a| the
// bound on the relative acceleration (the sum of the two sides' magnitudes).
template <typename T>
inline Mask<T> resting(const T closing_less_built, const T acceleration_bound, const Real h) {
  return closing_less_built >
         (Lane<T>::broadcast(-2.0) * acceleration_bound) * Lane<T>::broadcast(h);
}

// The same test for one moving side, whose |a| is sqrt(s): decided from the squares where they
// are clearly apart (rounding moves each side by some 1e-16 of it, far less than the 1e-9
// margin), else by the square root as above: the same answer without the square root's latency.
template <typename T>
inline Mask<T> restingOneSide(const T closing_less_built, const T s, const Real h) {
  using L = Lane<T>;
  const T limit_squared = L::broadcast(4.0 * h * h) * s;
  const Mask<T> in_range =
      L::both(limit_squared > L::broadcast(1e-250), limit_squared < L::broadcast(1e250));
  const T squared = closing_less_built * closing_less_built;
  const Mask<T> resting_by_squares = L::either(closing_less_built >= L::broadcast(0.0),
                                               squared < limit_squared * L::broadcast(1.0 - 1e-9));
  const Mask<T> moving_by_squares = squared > limit_squared * L::broadcast(1.0 + 1e-9);
  const Mask<T> decided = L::both(in_range, L::either(resting_by_squares, moving_by_squares));
  if (L::all(decided)) return resting_by_squares;
  const Mask<T> by_root = resting(closing_less_built, L::sqrt(s), h);
  return L::either(L::both(decided, resting_by_squares), L::both(L::negate(decided), by_root));
}

// m/s: a contact that held in the last substep bounces when it closes faster than this (a
// particle at rest kicked into what holds it; the bodies' default restitution threshold). Slower,
// it is what a pile's passes left unsolved, which a bounce would throw back up.
constexpr Real kHeldBounceSpeed = 1.0;

// The target separating velocity of a contact (or a cable: `resting_holds` false), fixed from the
// velocities before any impulse (the total impulse is what the passes converge, so a bounce must
// not be re-evaluated from a half-solved state), in this order of precedence:
// * resting, when its impulses will be followed in position (follow): aim at touching,
//   min(0, v_sep + p / (beta h)): a resting contact moves by beta h (v''_sep - v'_sep) after the
//   velocity phase, which leaves the overlap p - beta h (v''_sep - v'_sep); never at pushing
//   apart (overlap beyond the slop is the position phase's work);
// * a gap p < 0: it may close at up to p / h within the substep, no faster;
// * an impact (not resting, and it did not act in the last substep: `previous` <= 0, a contact
//   already pushing is holding, not hitting, unless it closes faster than kHeldBounceSpeed):
//   -e times the closing velocity less what the forces built while the contact existed,
//   d / |v_sep| of the substep for an overlap d;
// * else 0.
template <typename T>
inline T target(const Mask<T> is_resting, const bool resting_holds, const T v_sep, const T built,
                const T penetration, const T restitution, const T previous, const Real h,
                const bool follow, const Real inverse_follow_scale) {
  using L = Lane<T>;
  const T resting_target = minZero(v_sep + penetration * L::broadcast(inverse_follow_scale));
  // Every lane resting and followed (a settled pile): nothing else to weigh.
  if (resting_holds && follow && L::all(is_resting)) return resting_target;
  const T zero = L::broadcast(0.0);
  const Mask<T> gap = penetration < zero;
  const Mask<T> hit = L::either(previous <= zero, v_sep - built < L::broadcast(-kHeldBounceSpeed));
  const Mask<T> bounces = L::both(L::both(L::negate(is_resting), hit), L::negate(gap));
  T result = zero;
  if (L::any(bounces)) {
    const T fraction = penetration / (-v_sep * L::broadcast(h));
    // std::clamp(fraction, 0, 1)
    const T clamped =
        L::select(fraction < zero, zero,
                  L::select(L::broadcast(1.0) < fraction, L::broadcast(1.0), fraction));
    const T in_contact = L::select(v_sep < zero, clamped, L::broadcast(1.0));
    result = L::select(bounces, -restitution * minZero(v_sep - built * in_contact), zero);
  }
  if (L::any(gap)) result = L::select(gap, penetration / L::broadcast(h), result);
  if (resting_holds && follow) result = L::select(is_resting, resting_target, result);
  return result;
}

// The speed along a taut link that keeps its length through the substep's turn. Moved by h v
// from where they move from (x - beta h v, whatever beta), its ends change its length by
// stretch = -h v_sep + drift, the drift being what turning adds (>= 0, the norm is convex;
// (h v_t)^2 / (2 L) to first order): v_sep = drift / h = stretch / h + v_sep takes it back, the
// centripetal impulse. A row that only stops v_sep shortens v by 1 - cos(theta) each substep
// instead (theta the angle turned); this turns it. A turn of theta reflects v_sep
// (v sin(theta / 2) either way), so the speed is capped at |v_sep|: the row never speeds its
// ends up, even through a turn the substep cannot resolve (h v_t beyond L).
inline Real turnSpeed(const Real stretch, const Real v_sep, const Real h) {
  return std::min(stretch / h + v_sep, std::abs(v_sep));
}

// One Gauss-Seidel update of a constraint's accumulated impulse: j = (v_target - v_sep) m, with
// m = 1 / (w_a + w_b); a unilateral constraint (a contact pushes, a cable pulls) keeps its total
// >= 0, a rod acts either way.
template <typename T>
inline T accumulate(const T total, const T target, const T v_sep, const T effective_mass,
                    const bool unilateral) {
  const T next = total + (target - v_sep) * effective_mass;
  return unilateral ? maxZero(next) : next;
}

// Coulomb's cone: the friction impulse f scaled back to mu j_n where it is longer.
template <typename T>
inline void clampToCone(Vec<T>& f, const T friction, const T normal_total) {
  using L = Lane<T>;
  const T limit = friction * normal_total;
  const T magnitude = L::sqrt(dot(f, f));
  const Mask<T> beyond = magnitude > limit;
  if (!L::any(beyond)) return;
  const T scale = limit / magnitude;
  for (int k = 0; k < 3; ++k) f[k] = L::select(beyond, f[k] * scale, f[k]);
}

// The part of v across the normal: v - (v.n) n.
template <typename T>
inline Vec<T> tangential(const Vec<T>& v, const Vec<T>& normal) {
  const T along = dot(v, normal);
  Vec<T> out;
  for (int k = 0; k < 3; ++k) out[k] = v[k] - along * normal[k];
  return out;
}

// The warm start's friction impulse: the last one in the current tangent plane, within mu j_n.
template <typename T>
inline Vec<T> warmFriction(const Vec<T>& last, const Vec<T>& normal, const T friction,
                           const T normal_total) {
  Vec<T> f = tangential(last, normal);
  clampToCone(f, friction, normal_total);
  return f;
}

// Coulomb: the total tangential impulse removes the slip of the relative velocity but stays
// within mu j_n.
template <typename T>
inline Vec<T> coulomb(const Vec<T>& friction_total, const Vec<T>& relative_velocity,
                      const Vec<T>& normal, const T effective_mass, const T friction,
                      const T normal_total) {
  const Vec<T> slip = tangential(relative_velocity, normal);
  Vec<T> next;
  for (int k = 0; k < 3; ++k) next[k] = friction_total[k] - slip[k] * effective_mass;
  clampToCone(next, friction, normal_total);
  return next;
}

// Side a's share of a correction along the normal, w_a / (w_a + w_b) d (side b's: -w_b / ... d).
template <typename T>
inline T share(const T amount, const T w, const T w_sum) {
  return (amount * w) / w_sum;
}

// Eigen's vectors as one lane and back (the rows).
inline Vec<Real> lanes(const Vec3& v) { return Vec<Real>{{v.x(), v.y(), v.z()}}; }
inline Vec3 eigen(const Vec<Real>& v) { return Vec3(v[0], v[1], v[2]); }

// The overlap a position correction leaves: half the slop, or, for a contact between two
// particles, at least pair_least (the overlap it was made with less a share of the smaller radius;
// -inf for the others): std::max(slop / 2, pair_least).
template <typename T>
inline T leastDepth(const Real slop, const T pair_least) {
  using L = Lane<T>;
  const T half_slop = L::broadcast(0.5 * slop);
  return L::select(half_slop < pair_least, pair_least, half_slop);
}

// Whether an overlap is corrected (down to `least`): beyond the slop and beyond `least`.
template <typename T>
inline Mask<T> corrects(const T depth, const Real slop, const T least) {
  using L = Lane<T>;
  return L::both(depth > L::broadcast(slop), depth > least);
}

// One contact whose particles nothing else moves this substep (an isolated contact), per lane:
// a against a collider, or against particle b (kWithB). All its steps at once: the set-up and
// warm start, one Gauss-Seidel pass (exact for a lone row), friction, the follow of a resting
// contact's impulse, the closing speed left, the position correction.
template <typename T>
struct IsolatedContact {
  // in
  Mask<T> live;  // lanes that hold a contact
  T wa;
  T wb;  // 0 without b
  T penetration;
  T restitution;
  T friction;
  T previous;                // the warm start's normal impulse (0 when none)
  Vec<T> previous_friction;  // and its friction impulse (zero when none)
  Vec<T> normal;
  Vec<T> va;  // in: the velocities before the contact; out: solved
  Vec<T> vb;
  Vec<T> xa;  // in: positions; out: solved
  Vec<T> xb;
  Vec<T> aa;  // accelerations over the substep
  Vec<T> ab;
  T least_depth;  // what the position correction leaves at least (leastDepth())
  // out
  T total;                // the normal impulse to keep for the next substep (0 when inactive)
  Vec<T> friction_total;  // and the friction impulse
  Mask<T> active;         // counts in the stats
  Mask<T> touched_a;      // a's velocity or position changed
  Mask<T> touched_b;
  T closing;  // the closing speed left, for the stats
  T depth;    // the overlap left, for the stats
  Mask<T> corrected;
};

struct IsolatedParameters {
  Real h = 0.0;
  Real slop = 0.0;
  Real follow_scale = 0.0;  // beta h
  Real inverse_follow_scale = 0.0;
};

template <typename T, bool kWithB, bool kFriction>
inline __attribute__((always_inline)) void solveIsolated(const IsolatedParameters& p,
                                                         IsolatedContact<T>& c) {
  using L = Lane<T>;
  const T zero = L::broadcast(0.0);
  const Mask<T> nothing = zero > zero;
  const T w_sum = kWithB ? c.wa + c.wb : c.wa;
  // w_a + w_b <= 0: never active, never corrected.
  const Mask<T> live = L::both(c.live, L::negate(w_sum <= zero));
  const Mask<T> moves_a = c.wa > zero;
  const Mask<T> moves_b = kWithB ? c.wb > zero : nothing;
  const Vec<T> initial_a = c.va;
  const Vec<T> initial_b = c.vb;
  const Vec<T> initial_xa = c.xa;
  const Vec<T> initial_xb = c.xb;
  Vec<T> relative_acceleration;
  for (int k = 0; k < 3; ++k) {
    relative_acceleration[k] = L::select(moves_a, c.aa[k], zero);
    if (kWithB)
      relative_acceleration[k] =
          L::select(moves_b, relative_acceleration[k] - c.ab[k], relative_acceleration[k]);
  }
  Vec<T> relative_velocity = initial_a;
  if (kWithB) {
    for (int k = 0; k < 3; ++k) relative_velocity[k] = initial_a[k] - initial_b[k];
  }
  const T v_sep = dot(relative_velocity, c.normal);
  const T built = minZero(dot(relative_acceleration, c.normal) * L::broadcast(p.h));
  // One moving side: |a_a| alone (a fixed b adds no bound); two: both magnitudes.
  Mask<T> is_resting = restingOneSide(
      v_sep - built, L::select(moves_a, dot(relative_acceleration, relative_acceleration), zero),
      p.h);
  if (kWithB && L::any(L::both(live, moves_b))) {
    const T bound = L::select(moves_a, L::sqrt(dot(c.aa, c.aa)), zero) + L::sqrt(dot(c.ab, c.ab));
    is_resting = L::choose(moves_b, resting(v_sep - built, bound, p.h), is_resting);
  }
  const Mask<T> gap = c.penetration < zero;
  // Inactive: a gap closing fast; its depth is negative, below every stat and the slop.
  const Mask<T> active = L::both(live, L::negate(L::both(gap, L::negate(is_resting))));
  const bool follow = p.follow_scale > 0.0;
  const T target_velocity = target(is_resting, true, v_sep, built, c.penetration, c.restitution,
                                   c.previous, p.h, follow, p.inverse_follow_scale);

  // Warm start: the last impulses, the friction one in the current tangent plane within mu j_n.
  T total = maxZero(c.previous);
  // kFriction: some lane may rub (friction > 0); the others skip every friction step.
  const Mask<T> rubs = kFriction ? c.friction > zero : nothing;
  Vec<T> friction_total{zero, zero, zero};
  if (kFriction) {
    friction_total = warmFriction(c.previous_friction, c.normal, c.friction, total);
    for (int k = 0; k < 3; ++k) friction_total[k] = L::select(rubs, friction_total[k], zero);
  }
  const Mask<T> warm = total != zero;
  Mask<T> touched_a = warm;
  Mask<T> touched_b = kWithB ? warm : nothing;
  for (int k = 0; k < 3; ++k) {
    T impulse = total * c.normal[k];
    if (kFriction) impulse = L::select(rubs, impulse + friction_total[k], impulse);
    c.va[k] = L::select(warm, initial_a[k] + c.wa * impulse, initial_a[k]);
    if (kWithB) c.vb[k] = L::select(warm, initial_b[k] - c.wb * impulse, initial_b[k]);
  }
  // One Gauss-Seidel pass: exact for a lone row.
  const T effective_mass = L::broadcast(1.0) / w_sum;
  Vec<T> relative = c.va;
  if (kWithB) {
    for (int k = 0; k < 3; ++k) relative[k] = c.va[k] - c.vb[k];
  }
  const T next = accumulate(total, target_velocity, dot(relative, c.normal), effective_mass, true);
  const T j = next - total;
  total = next;
  const Mask<T> pushed = j != zero;
  for (int k = 0; k < 3; ++k) {
    c.va[k] = L::select(pushed, c.va[k] + (j * c.wa) * c.normal[k], c.va[k]);
    if (kWithB) c.vb[k] = L::select(pushed, c.vb[k] - (j * c.wb) * c.normal[k], c.vb[k]);
  }
  touched_a = L::either(touched_a, L::both(pushed, moves_a));
  if (kWithB) touched_b = L::either(touched_b, L::both(pushed, moves_b));
  if (kFriction) {
    Vec<T> relative_now = c.va;
    if (kWithB) {
      for (int k = 0; k < 3; ++k) relative_now[k] = c.va[k] - c.vb[k];
    }
    const Vec<T> friction_next =
        coulomb(friction_total, relative_now, c.normal, effective_mass, c.friction, total);
    for (int k = 0; k < 3; ++k) {
      const T change = friction_next[k] - friction_total[k];
      c.va[k] = L::select(rubs, c.va[k] + c.wa * change, c.va[k]);
      if (kWithB) c.vb[k] = L::select(rubs, c.vb[k] - c.wb * change, c.vb[k]);
      friction_total[k] = L::select(rubs, friction_next[k], zero);
    }
  }
  // Follow: dx = beta h (v - v_initial) for a resting contact's particles.
  Vec<T> move_a{zero, zero, zero};
  Vec<T> move_b{zero, zero, zero};
  if (follow) {
    const T scale = L::broadcast(p.follow_scale);
    const Mask<T> follows_a = L::both(is_resting, touched_a);
    const Mask<T> follows_b = L::both(is_resting, touched_b);
    for (int k = 0; k < 3; ++k) {
      move_a[k] = L::select(follows_a, scale * (c.va[k] - initial_a[k]), zero);
      c.xa[k] = L::select(follows_a, c.xa[k] + move_a[k], c.xa[k]);
      if (kWithB) {
        move_b[k] = L::select(follows_b, scale * (c.vb[k] - initial_b[k]), zero);
        c.xb[k] = L::select(follows_b, c.xb[k] + move_b[k], c.xb[k]);
      }
    }
  }
  // min(0, p / h) - v_sep: the closing speed left.
  Vec<T> relative_after = c.va;
  if (kWithB) {
    for (int k = 0; k < 3; ++k) relative_after[k] = c.va[k] - c.vb[k];
  }
  c.closing =
      L::select(gap, c.penetration / L::broadcast(p.h), zero) - dot(relative_after, c.normal);
  // Position: overlap beyond the slop down to half the slop, dp_a = w_a / (w_a + w_b) d n.
  Vec<T> moved = move_a;
  if (kWithB) {
    for (int k = 0; k < 3; ++k) moved[k] = move_a[k] - move_b[k];
  }
  T depth = c.penetration - dot(moved, c.normal);
  const Mask<T> corrected = L::both(active, corrects(depth, p.slop, c.least_depth));
  if (L::any(corrected)) {
    const T amount = depth - c.least_depth;
    const T share_a = share(amount, c.wa, w_sum);
    const T share_b = kWithB ? share(-amount, c.wb, w_sum) : zero;
    for (int k = 0; k < 3; ++k) {
      const T correction_a = share_a * c.normal[k];
      c.xa[k] = L::select(corrected, c.xa[k] + correction_a, c.xa[k]);
      move_a[k] = L::select(corrected, move_a[k] + correction_a, move_a[k]);
      if (kWithB) {
        const T correction_b = share_b * c.normal[k];
        c.xb[k] = L::select(corrected, c.xb[k] + correction_b, c.xb[k]);
        move_b[k] = L::select(corrected, move_b[k] + correction_b, move_b[k]);
      }
    }
    Vec<T> moved_after = move_a;
    if (kWithB) {
      for (int k = 0; k < 3; ++k) moved_after[k] = move_a[k] - move_b[k];
    }
    depth = L::select(corrected, c.penetration - dot(moved_after, c.normal), depth);
    touched_a = L::either(touched_a, L::both(corrected, moves_a));
    if (kWithB) touched_b = L::either(touched_b, L::both(corrected, moves_b));
  }
  c.depth = depth;
  c.corrected = corrected;
  c.active = active;
  c.touched_a = L::both(touched_a, active);
  c.touched_b = L::both(touched_b, active);
  c.total = L::select(active, total, zero);
  for (int k = 0; k < 3; ++k) c.friction_total[k] = L::select(active, friction_total[k], zero);
  // Particles not touched keep what they loaded: the same bits.
  for (int k = 0; k < 3; ++k) {
    c.va[k] = L::select(c.touched_a, c.va[k], initial_a[k]);
    c.xa[k] = L::select(c.touched_a, c.xa[k], initial_xa[k]);
    if (kWithB) {
      c.vb[k] = L::select(c.touched_b, c.vb[k], initial_b[k]);
      c.xb[k] = L::select(c.touched_b, c.xb[k], initial_xb[k]);
    }
  }
}

}  // namespace response
}  // namespace engine
}  // namespace mass_aggregate_sim
