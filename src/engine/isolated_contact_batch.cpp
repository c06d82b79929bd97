#include "mass_aggregate_sim/engine/isolated_contact_batch.h"

#include <algorithm>
#include <cmath>

#include "mass_aggregate_sim/engine/simd.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

using simd::broadcast;
using simd::Mask4;
using simd::Real4;
using simd::select;

// Eigen's order for a 3-vector dot product: (a0 b0 + a1 b1) + a2 b2.
inline Real4 dot(const Real4 (&a)[3], const Real4 (&b)[3]) {
  return (a[0] * b[0] + a[1] * b[1]) + a[2] * b[2];
}

// std::min(0, value) and std::max(0, value) lane by lane: (value < 0 ? value : 0) and
// (0 < value ? value : 0), so a NaN gives 0 as it does there.
inline Real4 minZero(const Real4 value) {
  return select(value < broadcast(0.0), value, broadcast(0.0));
}
inline Real4 maxZero(const Real4 value) {
  return select(broadcast(0.0) < value, value, broadcast(0.0));
}

inline bool anySet(const Mask4 mask) { return (mask[0] | mask[1] | mask[2] | mask[3]) != 0; }

// restingWithOne() of contact_resolver.cpp on four lanes: the squares decide where they are
// clearly apart, the square root's comparison elsewhere (computed only when a lane needs it: it is
// on the chain every later step waits for).
inline Mask4 restingWithOne(const Real4 closing_less_built, const Real4 s, const Real h) {
  const Real4 limit_squared = broadcast(4.0 * h * h) * s;
  const Mask4 in_range = (limit_squared > broadcast(1e-250)) & (limit_squared < broadcast(1e250));
  const Real4 squared = closing_less_built * closing_less_built;
  const Mask4 resting_by_squares =
      (closing_less_built >= broadcast(0.0)) | (squared < limit_squared * broadcast(1.0 - 1e-9));
  const Mask4 moving_by_squares = squared > limit_squared * broadcast(1.0 + 1e-9);
  const Mask4 decided = in_range & (resting_by_squares | moving_by_squares);
  if (simd::allSet(decided)) return resting_by_squares;
  Real4 root;
  for (int l = 0; l < 4; ++l) root[l] = std::sqrt(s[l]);
  const Mask4 by_root = closing_less_built > (broadcast(-2.0) * root) * broadcast(h);
  return (decided & resting_by_squares) | (~decided & by_root);
}

// The inputs as locals: stores through x and v cannot change them, so they stay in registers.
struct Lanes {
  const Contact* contacts;
  const std::uint32_t* contact_index;
  const Real* previous_impulse;
  const Real* inverse_mass;
  const Real* acceleration;
  std::ptrdiff_t acceleration_stride;
  Real h;
  Real slop;
  Real follow_scale;
  Real inverse_follow_scale;
};

// What the lanes add up over the batches, kept in registers: the stats as lane-wise maxima (the
// order does not matter: std::max skips a NaN either way and all start from +0) and the written
// particles' count.
struct Running {
  Real4 max_closing;
  Real4 max_penetration;
  Mask4 corrected;
  std::size_t touched_count;
};

// std::max(acc, value) lane by lane.
inline Real4 runningMax(const Real4 acc, const Real4 value) {
  return select(acc < value, value, acc);
}

// xyz of four consecutive particles, (x0 y0 z0 x1) (y1 z1 x2 y2) (z2 x3 y3 z3) in memory, to and
// from one Real4 per component.
inline void transposeIn(const Real* p, Real4 (&out)[3]) {
  const Real4 a = simd::load(p);
  const Real4 b = simd::load(p + 4);
  const Real4 c = simd::load(p + 8);
  const Real4 xs = __builtin_shufflevector(a, b, 0, 3, 6, 7);  // x0 x1 x2 y2
  const Real4 ys = __builtin_shufflevector(a, b, 1, 4, 7, 7);  // y0 y1 y2 y2
  const Real4 zs = __builtin_shufflevector(a, b, 2, 5, 5, 5);  // z0 z1 z1 z1
  out[0] = __builtin_shufflevector(xs, c, 0, 1, 2, 5);
  out[1] = __builtin_shufflevector(ys, c, 0, 1, 2, 6);
  out[2] = __builtin_shufflevector(zs, c, 0, 1, 4, 7);
}

inline void transposeOut(const Real4 (&in)[3], Real* p) {
  const Real4 xy = __builtin_shufflevector(in[0], in[1], 0, 4, 1, 5);   // x0 y0 x1 y1
  const Real4 yz = __builtin_shufflevector(in[1], in[2], 1, 5, 2, 6);   // y1 z1 y2 z2
  const Real4 xy3 = __builtin_shufflevector(in[0], in[1], 3, 7, 3, 7);  // x3 y3 x3 y3
  simd::store(p, __builtin_shufflevector(xy, in[2], 0, 1, 4, 2));
  simd::store(p + 4, __builtin_shufflevector(yz, in[0], 0, 1, 6, 2));
  simd::store(p + 8, __builtin_shufflevector(in[2], xy3, 2, 4, 5, 3));
}

// One contact per lane (no b, no friction), as solveIsolated<false> solves it: in.velocity and
// in.position come back solved, `total` is the impulse to keep, `active` and `touched` say which
// lanes count in the stats and which particles changed. Lanes outside `live` change nothing.
struct LaneContacts {
  Real4 w;  // inverse masses
  Real4 penetration;
  Real4 restitution;
  Real4 previous;  // warm starts
  Real4 normal[3];
  Real4 velocity[3];  // in: initial
  Real4 position[3];
  Real4 acceleration[3];
  Mask4 live;
  Real4 total;
  Mask4 active;
  Mask4 touched;
};

template <bool kFollow>
inline __attribute__((always_inline)) void solveLanes(const Lanes& lanes, LaneContacts& in,
                                                      Running& running) {
  const Real4 zero = broadcast(0.0);
  const Real4 w = in.w;
  const Real4 penetration = in.penetration;
  const Real4 restitution = in.restitution;
  const Real4 previous = in.previous;
  const Mask4 movable = w > zero;
  const Mask4 live = in.live;
  const Real4(&normal)[3] = in.normal;
  Real4(&position)[3] = in.position;
  Real4(&acceleration)[3] = in.acceleration;
  const Real4 initial[3] = {in.velocity[0], in.velocity[1], in.velocity[2]};
  for (int k = 0; k < 3; ++k) acceleration[k] = select(movable, acceleration[k], zero);
  const Real4 h = broadcast(lanes.h);
  const Real4 v_sep = dot(initial, normal);
  const Real4 built = minZero(dot(acceleration, normal) * h);
  const Mask4 resting = restingWithOne(v_sep - built, dot(acceleration, acceleration), lanes.h);
  const Mask4 gap = penetration < zero;
  // Inactive: a gap closing fast; its depth is negative, below every stat and the slop.
  const Mask4 active = live & ~(gap & ~resting);

  // The target separating velocity, in the order of the scalar branches.
  const Mask4 bounces = ~resting & (previous <= zero) & ~gap;
  Real4 target = zero;
  if (anySet(bounces)) {
    // Closing velocity the forces built, for the fraction of the substep in contact.
    const Real4 fraction = penetration / (-v_sep * h);
    // std::clamp(fraction, 0, 1)
    const Real4 clamped =
        select(fraction < zero, zero, select(broadcast(1.0) < fraction, broadcast(1.0), fraction));
    const Real4 in_contact = select(v_sep < zero, clamped, broadcast(1.0));
    const Real4 bounce_target = -restitution * minZero(v_sep - built * in_contact);
    target = select(bounces, bounce_target, zero);
  }
  // A gap may close at up to p / h within the substep.
  const Real4 gap_target = anySet(gap) ? penetration / h : zero;
  target = select(gap, gap_target, target);
  if constexpr (kFollow) {
    const Real4 resting_target =
        minZero(v_sep + penetration * broadcast(lanes.inverse_follow_scale));
    target = select(resting, resting_target, target);
  }

  Real4 total = maxZero(previous);
  Real4(&velocity)[3] = in.velocity;
  const Mask4 warm = total != zero;
  Mask4 touched = warm;
  for (int k = 0; k < 3; ++k)
    velocity[k] = select(warm, initial[k] + w * (total * normal[k]), initial[k]);
  // One Gauss-Seidel pass: exact for a lone row.
  const Real4 effective_mass = broadcast(1.0) / w;
  const Real4 next = maxZero(total + (target - dot(velocity, normal)) * effective_mass);
  const Real4 j = next - total;
  total = next;
  const Mask4 pushed = j != zero;
  for (int k = 0; k < 3; ++k) {
    velocity[k] = select(pushed, velocity[k] + (j * w) * normal[k], velocity[k]);
  }
  touched |= pushed & movable;
  // Follow: dx = beta h (v - v_initial) for a resting contact's particle.
  Real4 move[3] = {zero, zero, zero};
  if constexpr (kFollow) {
    const Mask4 follows = resting & touched;
    const Real4 scale = broadcast(lanes.follow_scale);
    for (int k = 0; k < 3; ++k) {
      move[k] = select(follows, scale * (velocity[k] - initial[k]), zero);
      position[k] = select(follows, position[k] + move[k], position[k]);
    }
  }
  // min(0, p / h) - v_sep: the closing speed left.
  const Real4 closing = select(gap, gap_target, zero) - dot(velocity, normal);
  // Position: overlap beyond the slop down to half the slop.
  Real4 depth = penetration - dot(move, normal);
  const Mask4 corrects = active & (depth > broadcast(lanes.slop));
  if (anySet(corrects)) {
    const Real4 correction = depth - broadcast(0.5 * lanes.slop);
    const Real4 share = (correction * w) / w;
    for (int k = 0; k < 3; ++k) {
      const Real4 correction_k = share * normal[k];
      position[k] = select(corrects, position[k] + correction_k, position[k]);
      move[k] = select(corrects, move[k] + correction_k, move[k]);
    }
    depth = select(corrects, penetration - dot(move, normal), depth);
  }
  touched |= corrects & movable;
  touched &= active;
  running.max_closing =
      select(active, runningMax(running.max_closing, closing), running.max_closing);
  running.max_penetration =
      select(active, runningMax(running.max_penetration, depth), running.max_penetration);
  running.corrected |= corrects;
  // Lanes not touched keep what they loaded: the same bits (an inactive lane's velocity may have
  // taken its warm start in the lanes, which the scalar code never applies).
  for (int k = 0; k < 3; ++k) velocity[k] = select(touched, velocity[k], initial[k]);
  in.total = total;
  in.active = active;
  in.touched = touched;
}

template <bool kFollow>
inline __attribute__((always_inline)) void solveFour(const Lanes& lanes, const std::size_t e,
                                                     Real* __restrict x, Real* __restrict v,
                                                     Real* __restrict next_warm_normal,
                                                     std::uint32_t* __restrict touched_out,
                                                     Running& running) {
  std::uint32_t contact[4];
  const Contact* c[4];
  std::size_t particle[4];
  for (int l = 0; l < 4; ++l) {
    contact[l] = lanes.contact_index[e + l];
    c[l] = lanes.contacts + contact[l];
    particle[l] = c[l]->a;
  }
  const Real4 zero = broadcast(0.0);
  LaneContacts lane{};
  lane.w = Real4{lanes.inverse_mass[particle[0]], lanes.inverse_mass[particle[1]],
                 lanes.inverse_mass[particle[2]], lanes.inverse_mass[particle[3]]};
  lane.penetration =
      Real4{c[0]->penetration, c[1]->penetration, c[2]->penetration, c[3]->penetration};
  lane.restitution =
      Real4{c[0]->restitution, c[1]->restitution, c[2]->restitution, c[3]->restitution};
  lane.previous = simd::load(lanes.previous_impulse + e);
  // w_sum <= 0: never active, never corrected.
  lane.live = ~(lane.w <= zero);
  for (int k = 0; k < 3; ++k) {
    lane.normal[k] = Real4{c[0]->normal[k], c[1]->normal[k], c[2]->normal[k], c[3]->normal[k]};
  }
  // Four particles one after the other (a row of balls on the ground): three loads and a transpose
  // per array instead of twelve single loads.
  const bool consecutive = particle[1] == particle[0] + 1 && particle[2] == particle[0] + 2 &&
                           particle[3] == particle[0] + 3 && lanes.acceleration_stride == 3;
  if (consecutive) {
    const std::size_t first = 3 * particle[0];
    transposeIn(x + first, lane.position);
    transposeIn(v + first, lane.velocity);
    transposeIn(lanes.acceleration + first, lane.acceleration);
  } else {
    const std::ptrdiff_t stride = lanes.acceleration_stride;
    for (int k = 0; k < 3; ++k) {
      lane.velocity[k] = Real4{v[3 * particle[0] + k], v[3 * particle[1] + k],
                               v[3 * particle[2] + k], v[3 * particle[3] + k]};
      lane.position[k] = Real4{x[3 * particle[0] + k], x[3 * particle[1] + k],
                               x[3 * particle[2] + k], x[3 * particle[3] + k]};
      lane.acceleration[k] =
          Real4{lanes.acceleration[stride * static_cast<std::ptrdiff_t>(particle[0]) + k],
                lanes.acceleration[stride * static_cast<std::ptrdiff_t>(particle[1]) + k],
                lanes.acceleration[stride * static_cast<std::ptrdiff_t>(particle[2]) + k],
                lanes.acceleration[stride * static_cast<std::ptrdiff_t>(particle[3]) + k]};
    }
  }
  solveLanes<kFollow>(lanes, lane, running);
  const Real4(&velocity)[3] = lane.velocity;
  const Real4(&solved)[3] = lane.position;
  const Real4 total = lane.total;
  const Mask4 active = lane.active;
  const Mask4 touched = lane.touched;
  if (consecutive) {
    const std::size_t first = 3 * particle[0];
    transposeOut(velocity, v + first);
    transposeOut(solved, x + first);
  } else {
    for (int l = 0; l < 4; ++l) {
      for (int k = 0; k < 3; ++k) {
        v[3 * particle[l] + k] = velocity[k][l];
        x[3 * particle[l] + k] = solved[k][l];
      }
    }
  }
  for (int l = 0; l < 4; ++l) {
    next_warm_normal[contact[l]] = active[l] ? total[l] : 0.0;
    touched_out[running.touched_count] = static_cast<std::uint32_t>(particle[l]);
    running.touched_count += static_cast<std::size_t>(touched[l] & 1);
  }
}

MAS_SIMD_CLONES void dispatch(const IsolatedBatchInputs& in, Real* x, Real* v,
                              IsolatedBatchOutputs& out) {
  const Lanes lanes{in.contacts,
                    in.contact_index,
                    in.previous_impulse,
                    in.inverse_mass,
                    in.acceleration,
                    in.acceleration_stride,
                    in.h,
                    in.slop,
                    in.follow_scale,
                    in.inverse_follow_scale};
  Running running{Real4{}, Real4{}, Mask4{}, 0};  // +0 maxima, nothing corrected or written
  Real* const next_warm_normal = out.next_warm_normal;
  std::uint32_t* const touched = out.touched + out.touched_count;
  const bool follow = in.follow_scale > 0.0;
  for (std::size_t e = 0; e + 4 <= in.count; e += 4) {
    follow ? solveFour<true>(lanes, e, x, v, next_warm_normal, touched, running)
           : solveFour<false>(lanes, e, x, v, next_warm_normal, touched, running);
  }
  out.touched_count += running.touched_count;
  for (int l = 0; l < 4; ++l) {
    out.max_closing = std::max(out.max_closing, running.max_closing[l]);
    out.max_penetration = std::max(out.max_penetration, running.max_penetration[l]);
    out.corrected = out.corrected || running.corrected[l] != 0;
  }
}

// Whether the contact named `key` is the next warm start (a settled scene lists its contacts in
// the same order every substep); its impulse in `previous`.
inline bool warmAtCursor(const PlaneGroupInputs& in, std::size_t& cursor, const std::uint64_t key,
                         Real& previous) {
  if (cursor >= in.warm_size || in.warm_key[cursor] != key) return false;
  previous = in.warm_normal[cursor++];
  return true;
}

// One group of four consecutive particles from `i`; false (nothing written) when a particle
// meets two planes or a warm start is not at the cursor.
template <bool kFollow>
inline __attribute__((always_inline)) bool solvePlaneGroup(const PlaneGroupInputs& in,
                                                           const Lanes& lanes, const std::size_t i,
                                                           Real* __restrict x, Real* __restrict v,
                                                           PlaneGroupOutputs& out,
                                                           Running& running) {
  const Real4 zero = broadcast(0.0);
  const Real4 w = simd::load(in.inverse_mass + i);
  // World::generateColliderContacts() skips particles with w <= 0.
  const Mask4 live = ~(w <= zero);
  Real4 position[3];
  transposeIn(x + 3 * i, position);
  const Real4 radius = simd::load(in.radius + i);
  // sphereVsPlane as the generation computes it: p = r - (n.x - offset), a contact when p >
  // -margin.
  Mask4 one{};
  Mask4 more{};
  Mask4 plane{};
  Real4 penetration = zero;
  Real4 restitution = zero;
  Real4 normal[3] = {zero, zero, zero};
  for (std::size_t p = 0; p < in.plane_count; ++p) {
    const BatchPlane& c = in.planes[p];
    const Real4 distance =
        (broadcast(c.normal[0]) * position[0] + broadcast(c.normal[1]) * position[1]) +
        broadcast(c.normal[2]) * position[2];
    const Real4 depth = radius - (distance - broadcast(c.offset));
    const Mask4 touches = live & (depth > broadcast(-in.margin));
    more |= one & touches;
    one |= touches;
    penetration = select(touches, depth, penetration);
    restitution = select(touches, broadcast(c.restitution), restitution);
    for (int k = 0; k < 3; ++k) normal[k] = select(touches, broadcast(c.normal[k]), normal[k]);
    plane = (plane & ~touches) | ((Mask4{} + static_cast<std::int64_t>(p)) & touches);
  }
  if (anySet(more)) return false;
  if (!anySet(one)) return true;  // all four in the air: nothing to write
  std::size_t cursor = out.cursor;
  Real previous[4] = {0.0, 0.0, 0.0, 0.0};
  std::uint64_t key[4] = {0, 0, 0, 0};
  for (int l = 0; l < 4; ++l) {
    if (!one[l]) continue;
    key[l] = colliderContactKey(in.slots[i + l], in.planes[plane[l]].id);
    if (!warmAtCursor(in, cursor, key[l], previous[l])) return false;
  }
  out.cursor = cursor;
  LaneContacts lane{w,
                    penetration,
                    restitution,
                    simd::load(previous),
                    {normal[0], normal[1], normal[2]},
                    {},
                    {position[0], position[1], position[2]},
                    {},
                    one,
                    zero,
                    Mask4{},
                    Mask4{}};
  transposeIn(v + 3 * i, lane.velocity);
  transposeIn(in.acceleration + 3 * i, lane.acceleration);
  solveLanes<kFollow>(lanes, lane, running);
  transposeOut(lane.velocity, v + 3 * i);
  transposeOut(lane.position, x + 3 * i);
  for (int l = 0; l < 4; ++l) {
    if (!one[l]) continue;
    out.next_warm_key[out.contacts] = key[l];
    out.next_warm_normal[out.contacts] = lane.active[l] ? lane.total[l] : 0.0;
    ++out.contacts;
    out.touched[out.touched_count] = static_cast<std::uint32_t>(i + l);
    out.touched_count += static_cast<std::size_t>(lane.touched[l] & 1);
  }
  return true;
}

MAS_SIMD_CLONES void planeDispatch(const PlaneGroupInputs& in, Real* x, Real* v,
                                   PlaneGroupOutputs& out) {
  const Lanes lanes{nullptr, nullptr, nullptr, in.inverse_mass, in.acceleration,
                    3,       in.h,    in.slop, in.follow_scale, in.inverse_follow_scale};
  Running running{Real4{}, Real4{}, Mask4{}, 0};  // +0 maxima, nothing corrected or written
  const bool follow = in.follow_scale > 0.0;
  std::size_t i = in.begin;
  for (; i + 4 <= in.end; i += 4) {
    const bool solved = follow ? solvePlaneGroup<true>(in, lanes, i, x, v, out, running)
                               : solvePlaneGroup<false>(in, lanes, i, x, v, out, running);
    if (!solved) break;
  }
  out.stopped = i;
  for (int l = 0; l < 4; ++l) {
    out.max_closing = std::max(out.max_closing, running.max_closing[l]);
    out.max_penetration = std::max(out.max_penetration, running.max_penetration[l]);
    out.corrected = out.corrected || running.corrected[l] != 0;
  }
}

}  // namespace

void solveIsolatedBatch(const IsolatedBatchInputs& in, Real* x, Real* v,
                        IsolatedBatchOutputs& out) {
  dispatch(in, x, v, out);
}

std::size_t solvePlaneGroups(const PlaneGroupInputs& in, Real* x, Real* v, PlaneGroupOutputs& out) {
  planeDispatch(in, x, v, out);
  return out.stopped;
}

}  // namespace engine
}  // namespace mass_aggregate_sim
