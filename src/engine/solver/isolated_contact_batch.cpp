#include "engine/solver/isolated_contact_batch.h"

#include <algorithm>
#include <cmath>

#include "engine/core/simd.h"
#include "engine/solver/contact_response.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

using simd::broadcast;
using simd::Mask4;
using simd::Real4;
using simd::select;

inline bool anySet(const Mask4 mask) { return (mask[0] | mask[1] | mask[2] | mask[3]) != 0; }

// The inputs as locals: stores through x and v cannot change them, so they stay in registers.
struct Lanes {
  const Contact* contacts;
  const std::uint32_t* contact_index;
  const Real* previous_impulse;
  const Real* previous_friction;
  const Real* inverse_mass;
  const Real* acceleration;
  std::ptrdiff_t acceleration_stride;
  Real h;
  Real slop;
  Real follow_scale;
  Real inverse_follow_scale;
};

// What the lanes add up over the batches, kept in registers: the stats as lane-wise maxima (the
// order does not matter: std::max skips a NaN either way and all start from +0), the written
// particles' count and whether an active contact had friction.
struct Running {
  Real4 max_closing;
  Real4 max_penetration;
  Mask4 corrected;
  std::size_t touched_count;
  bool rubbed;
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

using LaneContacts = response::IsolatedContact<Real4>;

// The contacts of the lanes (no b) solved by the one contact response, the stats added up.
template <bool kFriction>
inline __attribute__((always_inline)) void solveLanes(const Lanes& lanes, LaneContacts& in,
                                                      Running& running) {
  const response::IsolatedParameters parameters{lanes.h, lanes.slop, lanes.follow_scale,
                                                lanes.inverse_follow_scale};
  response::solveIsolated<Real4, false, kFriction>(parameters, in);
  running.max_closing =
      select(in.active, runningMax(running.max_closing, in.closing), running.max_closing);
  running.max_penetration =
      select(in.active, runningMax(running.max_penetration, in.depth), running.max_penetration);
  running.corrected |= in.corrected;
}

inline __attribute__((always_inline)) void solveFour(const Lanes& lanes, const std::size_t e,
                                                     Real* __restrict x, Real* __restrict v,
                                                     Real* __restrict next_warm_normal,
                                                     Real* __restrict next_warm_friction,
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
  lane.wa = Real4{lanes.inverse_mass[particle[0]], lanes.inverse_mass[particle[1]],
                  lanes.inverse_mass[particle[2]], lanes.inverse_mass[particle[3]]};
  lane.penetration =
      Real4{c[0]->penetration, c[1]->penetration, c[2]->penetration, c[3]->penetration};
  lane.restitution =
      Real4{c[0]->restitution, c[1]->restitution, c[2]->restitution, c[3]->restitution};
  lane.previous = simd::load(lanes.previous_impulse + e);
  lane.friction = Real4{c[0]->friction, c[1]->friction, c[2]->friction, c[3]->friction};
  const Mask4 rubs = lane.friction > zero;
  const bool any_rubs = anySet(rubs);
  if (any_rubs) {
    transposeIn(lanes.previous_friction + 3 * e, lane.previous_friction.c);
  }
  // w_sum <= 0: never active, never corrected.
  lane.live = ~(lane.wa <= zero);
  lane.least_depth = broadcast(response::leastDepth(lanes.slop, -response::kInfinity));
  for (int k = 0; k < 3; ++k) {
    lane.normal[k] = Real4{c[0]->normal[k], c[1]->normal[k], c[2]->normal[k], c[3]->normal[k]};
  }
  // Four particles one after the other (a row of balls on the ground): three loads and a transpose
  // per array instead of twelve single loads.
  const bool consecutive = particle[1] == particle[0] + 1 && particle[2] == particle[0] + 2 &&
                           particle[3] == particle[0] + 3 && lanes.acceleration_stride == 3;
  if (consecutive) {
    const std::size_t first = 3 * particle[0];
    transposeIn(x + first, lane.xa.c);
    transposeIn(v + first, lane.va.c);
    transposeIn(lanes.acceleration + first, lane.aa.c);
  } else {
    const std::ptrdiff_t stride = lanes.acceleration_stride;
    for (int k = 0; k < 3; ++k) {
      lane.va[k] = Real4{v[3 * particle[0] + k], v[3 * particle[1] + k], v[3 * particle[2] + k],
                         v[3 * particle[3] + k]};
      lane.xa[k] = Real4{x[3 * particle[0] + k], x[3 * particle[1] + k], x[3 * particle[2] + k],
                         x[3 * particle[3] + k]};
      lane.aa[k] = Real4{lanes.acceleration[stride * static_cast<std::ptrdiff_t>(particle[0]) + k],
                         lanes.acceleration[stride * static_cast<std::ptrdiff_t>(particle[1]) + k],
                         lanes.acceleration[stride * static_cast<std::ptrdiff_t>(particle[2]) + k],
                         lanes.acceleration[stride * static_cast<std::ptrdiff_t>(particle[3]) + k]};
    }
  }
  if (any_rubs) {
    solveLanes<true>(lanes, lane, running);
  } else {
    solveLanes<false>(lanes, lane, running);
  }
  const Real4(&velocity)[3] = lane.va.c;
  const Real4(&solved)[3] = lane.xa.c;
  const Real4 total = lane.total;
  const Mask4 active = lane.active;
  const Mask4 touched = lane.touched_a;
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
  if (!any_rubs) return;
  // As the scalar instance keeps them: only a rubbing contact's that pushed (an inactive one
  // keeps no impulse).
  for (int l = 0; l < 4; ++l) {
    if (!rubs[l] || !active[l]) continue;
    running.rubbed = true;
    if (total[l] == 0.0) continue;
    for (int k = 0; k < 3; ++k) {
      next_warm_friction[3 * contact[l] + k] = lane.friction_total[k][l];
    }
  }
}

MAS_SIMD_CLONES void dispatch(const IsolatedBatchInputs& in, Real* x, Real* v,
                              IsolatedBatchOutputs& out) {
  const Lanes lanes{in.contacts,     in.contact_index, in.previous_impulse,    in.previous_friction,
                    in.inverse_mass, in.acceleration,  in.acceleration_stride, in.h,
                    in.slop,         in.follow_scale,  in.inverse_follow_scale};
  // +0 maxima, nothing corrected, written or rubbed
  Running running{Real4{}, Real4{}, Mask4{}, 0, false};
  Real* const next_warm_normal = out.next_warm_normal;
  Real* const next_warm_friction = out.next_warm_friction;
  std::uint32_t* const touched = out.touched + out.touched_count;
  for (std::size_t e = 0; e + 4 <= in.count; e += 4) {
    solveFour(lanes, e, x, v, next_warm_normal, next_warm_friction, touched, running);
  }
  out.touched_count += running.touched_count;
  out.rubbed = out.rubbed || running.rubbed;
  for (int l = 0; l < 4; ++l) {
    out.max_closing = std::max(out.max_closing, running.max_closing[l]);
    out.max_penetration = std::max(out.max_penetration, running.max_penetration[l]);
    out.corrected = out.corrected || running.corrected[l] != 0;
  }
}

// Whether the contact named `key` is the next warm start (a settled scene lists its contacts in
// the same order every substep); its place in `found`.
inline bool warmAtCursor(const ColliderGroupInputs& in, std::size_t& cursor,
                         const std::uint64_t key, std::size_t& found) {
  if (cursor >= in.warm_size || in.warm_key[cursor] != key) return false;
  found = cursor++;
  return true;
}

// One group of four consecutive particles from `i`; false (nothing written) when a particle
// meets two colliders, a swept test stopped it, or a warm start is not at the cursor.
inline __attribute__((always_inline)) bool solveColliderGroup(
    const ColliderGroupInputs& in, const Lanes& lanes, const std::size_t i, Real* __restrict x,
    Real* __restrict v, ColliderGroupOutputs& out, Running& running) {
  const Real4 zero = broadcast(0.0);
  LaneContacts lane{};
  lane.wa = simd::load(in.inverse_mass + i);
  // generateColliderContacts() skips particles with w <= 0.
  const Mask4 live = ~(lane.wa <= zero);
  lane.least_depth = broadcast(response::leastDepth(lanes.slop, -response::kInfinity));
  transposeIn(x + 3 * i, lane.xa.c);
  const Real4 radius = simd::load(in.radius + i);
  // A contact when the depth p > -margin.
  Mask4 one{};
  Mask4 more{};
  Mask4 plane{};
  for (std::size_t p = 0; p < in.plane_count; ++p) {
    const BatchPlane& c = in.planes[p];
    const Real4 depth =
        ShapeKind<PlaneCollider>::depth(c.plane, lane.xa[0], lane.xa[1], lane.xa[2], radius);
    const Mask4 touches = live & (depth > broadcast(-in.margin));
    more |= one & touches;
    one |= touches;
    lane.penetration = select(touches, depth, lane.penetration);
    lane.restitution = select(touches, broadcast(c.restitution), lane.restitution);
    lane.friction = select(touches, broadcast(c.friction), lane.friction);
    for (int k = 0; k < 3; ++k) {
      lane.normal[k] = select(touches, broadcast(c.plane.normal[k]), lane.normal[k]);
    }
    plane = (plane & ~touches) | ((Mask4{} + static_cast<std::int64_t>(p)) & touches);
  }
  if (anySet(more)) return false;
  std::uint32_t collider[4] = {0, 0, 0, 0};
  for (int l = 0; l < 4; ++l) {
    if (one[l]) collider[l] = in.planes[plane[l]].plane.id;
  }
  if (in.others != nullptr) {
    for (int l = 0; l < 4; ++l) {
      if (!live[l]) continue;
      GroupContact contact;
      const int count = in.others(in.others_context, i + l, contact);
      if (count == 0) continue;
      if (count > 1 || one[l]) return false;
      one[l] = -1;
      collider[l] = contact.collider;
      lane.penetration[l] = contact.shape.penetration;
      lane.restitution[l] = contact.restitution;
      lane.friction[l] = contact.friction;
      for (int k = 0; k < 3; ++k) lane.normal[k][l] = contact.shape.normal[k];
    }
  }
  if (!anySet(one)) return true;  // all four in the air: nothing to write
  std::size_t cursor = out.cursor;
  std::uint64_t key[4] = {0, 0, 0, 0};
  for (int l = 0; l < 4; ++l) {
    if (!one[l]) continue;
    key[l] = colliderContactKey(in.slots[i + l], collider[l]);
    std::size_t found = 0;
    if (!warmAtCursor(in, cursor, key[l], found)) return false;
    lane.previous[l] = in.warm_normal[found];
    if (in.warm_friction != nullptr) {
      for (int k = 0; k < 3; ++k) lane.previous_friction[k][l] = in.warm_friction[3 * found + k];
    }
  }
  out.cursor = cursor;
  lane.live = one;
  transposeIn(v + 3 * i, lane.va.c);
  transposeIn(in.acceleration + 3 * i, lane.aa.c);
  const Mask4 rubs = one & (lane.friction > zero);
  if (anySet(rubs)) {
    solveLanes<true>(lanes, lane, running);
  } else {
    solveLanes<false>(lanes, lane, running);
  }
  transposeOut(lane.va.c, v + 3 * i);
  transposeOut(lane.xa.c, x + 3 * i);
  for (int l = 0; l < 4; ++l) {
    if (!one[l]) continue;
    const std::size_t made = out.contacts++;
    out.next_warm_key[made] = key[l];
    out.next_warm_normal[made] = lane.total[l];
    // As the scalar instance keeps them: only a rubbing contact's that pushed.
    if (rubs[l] && lane.total[l] != 0.0) {
      for (int k = 0; k < 3; ++k) out.next_warm_friction[3 * made + k] = lane.friction_total[k][l];
    }
    out.rubbed = out.rubbed || (rubs[l] && lane.active[l]);
    out.touched[out.touched_count] = static_cast<std::uint32_t>(i + l);
    out.touched_count += static_cast<std::size_t>(lane.touched_a[l] & 1);
  }
  return true;
}

MAS_SIMD_CLONES void groupDispatch(const ColliderGroupInputs& in, Real* x, Real* v,
                                   ColliderGroupOutputs& out) {
  const Lanes lanes{
      nullptr, nullptr, nullptr, nullptr,         in.inverse_mass,        in.acceleration,
      3,       in.h,    in.slop, in.follow_scale, in.inverse_follow_scale};
  // +0 maxima, nothing corrected or written (a group reports its friction in out.rubbed)
  Running running{Real4{}, Real4{}, Mask4{}, 0, false};
  std::size_t i = in.begin;
  for (; i + 4 <= in.end; i += 4) {
    if (!solveColliderGroup(in, lanes, i, x, v, out, running)) break;
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

std::size_t solveColliderGroups(const ColliderGroupInputs& in, Real* x, Real* v,
                                ColliderGroupOutputs& out) {
  groupDispatch(in, x, v, out);
  return out.stopped;
}

}  // namespace engine
}  // namespace mass_aggregate_sim
