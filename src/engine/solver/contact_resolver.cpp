#include "engine/solver/contact_resolver.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "engine/solver/contact_response.h"
#include "engine/solver/isolated_contact_batch.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

static_assert(!ParticleRow::kTurns, "the passes below solve rows between particles");

constexpr Real kMinLinkLength = 1e-12;
// How many rows ahead the passes ask for their data (a row is a cache line), when the rows take
// more than kStreamingBytes: smaller ones stay in the caches from pass to pass, and there the
// prefetch instructions cost more than they save (4 % at 10,000 particles in a pile).
constexpr std::size_t kPrefetchAhead = 32;
constexpr std::size_t kStreamingBytes = std::size_t{8} << 20;
// Of the smaller radius: how much of its overlap a particle pair's position correction may remove
// in one substep. Half a radius still pushes a sphere set down half a radius into another out at
// once (test CandidatePairs.SlowApproachAndTeleportStillCollide); in the dense drop of
// test/engine/world/dense_drop_test.cpp (r = 3 cm) the pile settled with bounds from 1 to 15 mm
// (10 and 15 mm also with 10,000 and 12,000 spheres) and seethed with 20 mm and 12,000.
constexpr Real kPairCorrectionShare = 0.5;

bool hasB(const Contact& c) { return c.b != kNoParticle; }

// A link's row takes back its turn (response::turnSpeed) only when its ends move from within 1 %
// of its length: the drift is a turn's for a link at its length, not for one the passes could not
// bring back. Every row of a 50-rod rope whipping at 1 substep aiming at its drift took the rope
// to 1e31 J per kg in 5 s; rows that only stop v_sep there keep what they did before.
constexpr Real kTurnTolerance = 0.01;

}  // namespace

Real ContactResolver::leastPairDepth(const std::uint32_t a, const std::uint32_t b,
                                     const Real penetration) const {
  if (radius_ == nullptr) return -response::kInfinity;
  return penetration - kPairCorrectionShare * std::min(radius_[a], radius_[b]);
}

bool ContactResolver::linkState(const Contact& c, const Vec3Map& x, const Real lead, Vec3& normal,
                                Real& error) const {
  const LinkGeometry& link = (*links_)[c.link];
  const auto end = [&](const std::uint32_t i) -> Vec3 {
    if (lead == 0.0) return x.col(i);
    return x.col(i) - lead * initial_velocity_.col(i);
  };
  const Vec3 other = hasB(c) ? end(c.b) : link.anchor;
  const Vec3 d = other - end(c.a);
  const Real length = d.norm();
  if (length < kMinLinkLength) return false;
  normal = d / length;
  error = length - link.length;
  return true;
}

void ContactResolver::indexWarmByKey() const {
  if (warm_by_key_.size() == warm_key_.size()) return;
  warm_by_key_.clear();
  for (std::size_t k = 0; k < warm_key_.size(); ++k) {
    warm_by_key_.emplace_back(warm_key_[k], static_cast<std::uint32_t>(k));
  }
  std::sort(warm_by_key_.begin(), warm_by_key_.end());
}

Real ContactResolver::lastImpulse(const std::uint64_t key) const {
  indexWarmByKey();
  const auto it = std::lower_bound(warm_by_key_.begin(), warm_by_key_.end(),
                                   std::pair<std::uint64_t, std::uint32_t>{key, 0});
  return it != warm_by_key_.end() && it->first == key ? warm_normal_[it->second] : 0.0;
}

bool ContactResolver::lastImpulses(const std::uint64_t key, Real& normal, Vec3& friction) const {
  indexWarmByKey();
  const auto it = std::lower_bound(warm_by_key_.begin(), warm_by_key_.end(),
                                   std::pair<std::uint64_t, std::uint32_t>{key, 0});
  if (it == warm_by_key_.end() || it->first != key) return false;
  normal = warm_normal_[it->second];
  friction = warm_friction_.empty() ? Vec3::Zero() : warm_friction_[it->second];
  return true;
}

void ContactResolver::keepImpulses(const std::size_t index, const std::uint64_t key,
                                   const Real normal, const Vec3& friction) {
  if (index >= warm_key_.size() || warm_key_[index] != key) return;
  warm_normal_[index] = normal;
  if (warm_friction_.empty()) {
    if (friction.isZero(0.0)) return;
    warm_friction_.assign(warm_key_.size(), Vec3::Zero());
  }
  warm_friction_[index] = friction;
}

std::ptrdiff_t ContactResolver::findWarm(const std::uint64_t key, std::size_t& cursor) {
  // A settled scene lists its contacts in the same order every substep: the entry is at the
  // cursor. Else a binary search by key, after which the cursor follows from there.
  if (cursor < warm_key_.size() && warm_key_[cursor] == key)
    return static_cast<std::ptrdiff_t>(cursor++);
  indexWarmByKey();
  const auto it = std::lower_bound(warm_by_key_.begin(), warm_by_key_.end(),
                                   std::pair<std::uint64_t, std::uint32_t>{key, 0});
  if (it == warm_by_key_.end() || it->first != key) return -1;
  cursor = it->second + std::size_t{1};
  return it->second;
}

void ContactResolver::solveVelocities(std::vector<Contact>& contacts,
                                      const std::vector<LinkGeometry>& links, Vec3Map x, Vec3Map v,
                                      const ConstScalarMap& inverse_mass,
                                      const Eigen::Ref<const Vec3Array>& acceleration, const Real h,
                                      const CollisionSettings& settings, const Real position_weight,
                                      ContactStats& stats, const IsolatedContacts isolated,
                                      const Real* const radius) {
  beginSubstep(x.cols(), h, position_weight, links);
  radius_ = radius;
  if (isolated == IsolatedContacts::kFind) {
    countParticleUses(contacts);
  } else {
    any_shared_ = isolated == IsolatedContacts::kNone;  // not looked for: every contact is a row
  }
  // With particles shared by several contacts (a pile) most contacts become rows: then |a| of
  // every particle in one vectorised loop and one copy of all velocities cost less than doing it
  // per row; otherwise (a few rows among isolated contacts) per row particle.
  beginPrepare(v, acceleration, any_shared_);
  prepare(contacts, 0, x, v, inverse_mass, acceleration, h, settings.penetration_slop, isolated);
  next_warm_key_.resize(prepared_count_);
  next_warm_normal_.resize(prepared_count_);
  if (!next_warm_friction_.empty()) next_warm_friction_.resize(prepared_count_, Vec3::Zero());
  if (!links.empty()) prepareLinkBlocks(inverse_mass, acceleration);
  stats.velocity_iterations = resolveVelocities(v, inverse_mass, settings);
  followRestingImpulses(x, v, inverse_mass);
}

void ContactResolver::correctPositions(const std::vector<Contact>& contacts, Vec3Map x, Vec3Map v,
                                       const ConstScalarMap& inverse_mass, const Real h,
                                       const CollisionSettings& settings, ContactStats& stats) {
  stats.position_iterations = resolvePositions(contacts, x, v, inverse_mass, h, settings, stats);
  // An isolated contact is solved in one velocity pass; a corrected one is measured again, as
  // the passes would in a second pass.
  if (isolated_corrected_) {
    stats.position_iterations =
        std::max(stats.position_iterations, std::min(2, std::max(1, settings.max_iterations)));
  }
  stats.max_penetration = std::max(stats.max_penetration, isolated_max_penetration_);
  stats.max_closing_velocity = std::max(stats.max_closing_velocity, isolated_max_closing_);
  stats.iterations = stats.velocity_iterations + stats.position_iterations;
  links_ = nullptr;
  radius_ = nullptr;
}

void ContactResolver::beginParts(const Eigen::Index particle_count, const Real h,
                                 const Real position_weight) {
  beginSubstep(particle_count, h, position_weight, no_links_);
  parts_size_ = 0;
  parts_prepared_ = false;
}

std::size_t ContactResolver::addColliderGroups(ColliderGroupInputs in, const bool any_friction,
                                               Vec3Map x, Vec3Map v,
                                               const ConstScalarMap& inverse_mass,
                                               const Eigen::Ref<const Vec3Array>& acceleration) {
  const std::size_t begin = in.begin;
  const std::size_t end = in.end;
  if (end < begin + 4 || acceleration.outerStride() != 3) return begin;
  preparePartsOnce(v, acceleration);
  // Room for a contact per particle (never more: a particle meeting two colliders stops them).
  const std::size_t room = parts_size_ + (end - begin);
  if (next_warm_key_.size() < room) {
    next_warm_key_.resize(room);
    next_warm_normal_.resize(room);
  }
  if (any_friction && next_warm_friction_.empty()) {
    next_warm_friction_.assign(next_warm_key_.size(), Vec3::Zero());
  }
  if (!next_warm_friction_.empty() && next_warm_friction_.size() < room) {
    next_warm_friction_.resize(room, Vec3::Zero());
  }
  const std::size_t touched_before = touched_.size();
  touched_.resize(touched_before + (end - begin));
  in.inverse_mass = inverse_mass.data();
  in.acceleration = acceleration.data();
  in.follow_scale = follow_scale_;
  in.inverse_follow_scale = inverse_follow_scale_;
  in.warm_key = warm_key_.data();
  in.warm_normal = warm_normal_.data();
  in.warm_friction = warm_friction_.empty() ? nullptr : warm_friction_.data()->data();
  in.warm_size = warm_key_.size();
  ColliderGroupOutputs out;
  out.cursor = warm_cursor_;
  out.next_warm_key = next_warm_key_.data() + parts_size_;
  out.next_warm_normal = next_warm_normal_.data() + parts_size_;
  out.next_warm_friction =
      next_warm_friction_.empty() ? nullptr : next_warm_friction_[parts_size_].data();
  out.touched = touched_.data() + touched_before;
  out.max_penetration = isolated_max_penetration_;
  out.max_closing = isolated_max_closing_;
  out.corrected = isolated_corrected_;
  const std::size_t stopped = solveColliderGroups(in, x.data(), v.data(), out);
  touched_.resize(touched_before + out.touched_count);
  warm_cursor_ = out.cursor;
  parts_size_ += out.contacts;
  prepared_count_ = parts_size_;
  isolated_count_ += out.contacts;
  isolated_max_penetration_ = out.max_penetration;
  isolated_max_closing_ = out.max_closing;
  isolated_corrected_ = out.corrected;
  any_friction_ = any_friction_ || out.rubbed;
  return stopped;
}

void ContactResolver::addPart(std::vector<Contact>& part, Vec3Map x, Vec3Map v,
                              const ConstScalarMap& inverse_mass,
                              const Eigen::Ref<const Vec3Array>& acceleration, const Real h,
                              const Real slop, const IsolatedContacts isolated) {
  preparePartsOnce(v, acceleration);
  if (isolated == IsolatedContacts::kFind) countParticleUses(part);
  prepare(part, parts_size_, x, v, inverse_mass, acceleration, h, slop, isolated);
  parts_size_ += part.size();
}

void ContactResolver::finishPartsVelocities(Vec3Map x, Vec3Map v,
                                            const ConstScalarMap& inverse_mass,
                                            const Eigen::Ref<const Vec3Array>& acceleration,
                                            const CollisionSettings& settings,
                                            ContactStats& stats) {
  preparePartsOnce(v, acceleration);  // no part: empty phases
  next_warm_key_.resize(prepared_count_);
  next_warm_normal_.resize(prepared_count_);
  if (!next_warm_friction_.empty()) next_warm_friction_.resize(prepared_count_, Vec3::Zero());
  stats.velocity_iterations = resolveVelocities(v, inverse_mass, settings);
  followRestingImpulses(x, v, inverse_mass);
}

void ContactResolver::preparePartsOnce(const Vec3Map& v,
                                       const Eigen::Ref<const Vec3Array>& acceleration) {
  if (parts_prepared_) return;
  beginPrepare(v, acceleration, false);
  parts_prepared_ = true;
}

void ContactResolver::beginSubstep(const Eigen::Index n, const Real h, const Real position_weight,
                                   const std::vector<LinkGeometry>& links) {
  // Isolated contacts' particles are in touched_ without a flag or a displacement entry.
  if (flagged_count_ > 0) {
    for (const std::uint32_t i : touched_) {
      if (!touched_flag_[i]) continue;
      touched_flag_[i] = 0;
      displacement_.col(i).setZero();
    }
  }
  touched_.clear();
  flagged_count_ = 0;
  // A resting contact's impulse is its load times h: a substep of another length (the bodies fell
  // asleep or woke, auto_substep) starts from the kept impulses scaled to it.
  if (last_substep_ > 0.0 && h != last_substep_) {
    const Real scale = h / last_substep_;
    for (Real& normal : warm_normal_) normal *= scale;
    for (Vec3& friction : warm_friction_) friction *= scale;
  }
  last_substep_ = h;
  links_ = &links;
  radius_ = nullptr;
  follow_scale_ = h * position_weight;
  // Once per substep, so each resting contact multiplies instead of dividing.
  inverse_follow_scale_ = follow_scale_ > 0.0 ? 1.0 / follow_scale_ : 0.0;
  if (displacement_.cols() != n) {
    displacement_.setZero(3, n);
    touched_flag_.assign(static_cast<std::size_t>(n), 0);
  }
  const auto particles = static_cast<std::size_t>(n);
  if (mixed_stamp_.size() != particles || ++stamp_ == 0) {
    mixed_stamp_.assign(particles, 0);
    rests_stamp_.assign(particles, 0);
    linked_stamp_.assign(particles, 0);
    initial_stamp_.assign(particles, 0);
    uses_.assign(particles, 0);
    stamp_ = 1;
  }
}

void ContactResolver::countParticleUses(const std::vector<Contact>& contacts) {
  const std::uint64_t once = std::uint64_t{stamp_} << 1;
  any_shared_ = false;
  const auto use = [&](const std::uint32_t i) {
    std::uint64_t& u = uses_[i];
    const bool seen = u == once || u == (once | 1);
    any_shared_ = any_shared_ || seen;
    u = seen ? (once | 1) : once;
  };
  for (const Contact& c : contacts) {
    use(c.a);
    if (hasB(c)) use(c.b);
  }
}

template <bool kWithB>
void ContactResolver::solveIsolated(const std::size_t k, const Contact& c, Vec3Map& x, Vec3Map& v,
                                    const ConstScalarMap& inverse_mass,
                                    const Eigen::Ref<const Vec3Array>& acceleration, const Real h,
                                    const Real slop, const Real previous_impulse,
                                    const Vec3* const previous_friction) {
  response::IsolatedContact<Real> lane;
  lane.live = true;
  lane.wa = inverse_mass[c.a];
  lane.wb = kWithB ? inverse_mass[c.b] : 0.0;
  lane.penetration = c.penetration;
  lane.restitution = c.restitution;
  lane.friction = c.friction;
  lane.previous = previous_impulse;
  const Vec3 no_friction = Vec3::Zero();
  const Vec3& warm_friction = previous_friction ? *previous_friction : no_friction;
  for (int d = 0; d < 3; ++d) {
    lane.previous_friction[d] = warm_friction[d];
    lane.normal[d] = c.normal[d];
    lane.va[d] = v(d, c.a);
    lane.xa[d] = x(d, c.a);
    lane.aa[d] = acceleration(d, c.a);
    lane.vb[d] = kWithB ? v(d, c.b) : 0.0;
    lane.xb[d] = kWithB ? x(d, c.b) : 0.0;
    lane.ab[d] = kWithB ? acceleration(d, c.b) : 0.0;
  }
  lane.least_depth = response::leastDepth(
      slop, kWithB ? leastPairDepth(c.a, c.b, c.penetration) : -response::kInfinity);
  const response::IsolatedParameters parameters{h, slop, follow_scale_, inverse_follow_scale_};
  const bool friction = c.friction > 0.0;
  if (friction) {
    response::solveIsolated<Real, kWithB, true>(parameters, lane);
  } else {
    response::solveIsolated<Real, kWithB, false>(parameters, lane);
  }
  next_warm_normal_[k] = lane.total;
  if (!lane.active) return;
  if (friction && lane.total != 0.0) {
    if (next_warm_friction_.empty())
      next_warm_friction_.assign(next_warm_key_.size(), Vec3::Zero());
    next_warm_friction_[k] =
        Vec3(lane.friction_total[0], lane.friction_total[1], lane.friction_total[2]);
  }
  any_friction_ = any_friction_ || friction;
  isolated_max_closing_ = std::max(isolated_max_closing_, lane.closing);
  isolated_max_penetration_ = std::max(isolated_max_penetration_, lane.depth);
  isolated_corrected_ = isolated_corrected_ || lane.corrected;
  if (lane.touched_a) {
    for (int d = 0; d < 3; ++d) {
      v(d, c.a) = lane.va[d];
      x(d, c.a) = lane.xa[d];
    }
    touched_.push_back(c.a);
  }
  if (kWithB && lane.touched_b) {
    for (int d = 0; d < 3; ++d) {
      v(d, c.b) = lane.vb[d];
      x(d, c.b) = lane.xb[d];
    }
    touched_.push_back(c.b);
  }
}

void ContactResolver::beginPrepare(const Vec3Map& v,
                                   const Eigen::Ref<const Vec3Array>& acceleration,
                                   const bool dense) {
  const Eigen::Index n = v.cols();
  if (initial_velocity_.cols() != n) initial_velocity_.resize(3, n);
  rows_dense_ = dense;
  if (rows_dense_) {
    acceleration_norm_.resize(acceleration.cols());
    for (Eigen::Index i = 0; i < acceleration.cols(); ++i) {
      acceleration_norm_[i] = acceleration.col(i).squaredNorm();
    }
    acceleration_norm_ = acceleration_norm_.array().sqrt();  // contiguous: packet square roots
    initial_velocity_ = v;
  }
  any_mixed_ = false;
  prepared_count_ = 0;
  next_warm_friction_.clear();
  any_friction_ = false;
  isolated_count_ = 0;
  isolated_max_penetration_ = 0.0;
  isolated_max_closing_ = 0.0;
  isolated_corrected_ = false;
  warm_cursor_ = 0;
  row_count_ = 0;
  blocks_.clear();
  fed_knots_.clear();
}

void ContactResolver::prepare(std::vector<Contact>& contacts, const std::size_t base, Vec3Map& x,
                              Vec3Map& v, const ConstScalarMap& inverse_mass,
                              const Eigen::Ref<const Vec3Array>& acceleration, const Real h,
                              const Real slop, const IsolatedContacts isolated) {
  const std::size_t count = contacts.size();
  const std::size_t total_count = base + count;
  const bool find_isolated = isolated != IsolatedContacts::kNone;
  const bool all_isolated = isolated == IsolatedContacts::kAll;
  // Never shrunk: growing back would value-initialise every row again.
  if (rows_.size() < row_count_ + count) {
    rows_.resize(row_count_ + count);
    row_contact_.resize(row_count_ + count);
    row_turn_.resize(row_count_ + count);
  }
  if (friction_total_.size() < row_count_ + count) {
    friction_coefficient_.resize(row_count_ + count);
    friction_total_.resize(row_count_ + count);
  }
  rows_are_contacts_ = !find_isolated;  // then base is 0: row k is contact k
  const bool prefetch = count * sizeof(Row) > kStreamingBytes;
  // Grown only, so adding parts does not fill them again; cut to size when the velocity phase
  // begins.
  if (next_warm_key_.size() < total_count) {
    next_warm_key_.resize(total_count);
    next_warm_normal_.resize(total_count);
  }
  if (!next_warm_friction_.empty() && next_warm_friction_.size() < total_count) {
    next_warm_friction_.resize(total_count, Vec3::Zero());
  }
  prepared_count_ = total_count;
  std::size_t cursor = warm_cursor_;
  std::size_t r = row_count_;
  // The batch holds indices into this call's contacts; their warm starts go at base + index.
  batch_base_ = base;
  for (std::size_t k = 0; k < count; ++k) {
    Contact& c = contacts[k];
    const bool b = hasB(c);
    const std::size_t g = base + k;  // its place among all the substep's contacts
    next_warm_key_[g] = c.key;
    // Inline the usual case: the entry at the cursor.
    const std::ptrdiff_t found = cursor < warm_key_.size() && warm_key_[cursor] == c.key
                                     ? static_cast<std::ptrdiff_t>(cursor++)
                                     : findWarm(c.key, cursor);
    if (find_isolated && c.kind == ContactKind::kContact && c.solvesVelocities() &&
        (all_isolated || (!isShared(c.a) && !(b && isShared(c.b))))) {
      ++isolated_count_;
      const bool warm_friction = found >= 0 && !warm_friction_.empty();
      const Real previous = found >= 0 ? warm_normal_[found] : 0.0;
      const Vec3* const previous_friction = warm_friction ? &warm_friction_[found] : nullptr;
      if (!b) {
        // The usual isolated contact (a ball on the ground): solved four at a time.
        batch_contact_[batch_count_] = static_cast<std::uint32_t>(k);
        batch_previous_[batch_count_] = previous;
        for (int d = 0; d < 3; ++d) {
          batch_previous_friction_[3 * batch_count_ + d] =
              previous_friction ? (*previous_friction)[d] : 0.0;
        }
        batch_rubs_ = batch_rubs_ || c.friction > 0.0;
        if (++batch_count_ == kBatchSize)
          flushIsolatedBatch(contacts, x, v, inverse_mass, acceleration, h, slop);
        continue;
      }
      solveIsolated<true>(g, c, x, v, inverse_mass, acceleration, h, slop, previous,
                          previous_friction);
      continue;
    }
    const std::size_t row_index = r++;
    // The contacts and rows stream through memory faster than the hardware prefetch follows
    // (a pile's do not fit in the caches): ask for them a few rows ahead.
    if (prefetch) {
      __builtin_prefetch(&contacts[std::min(k + kPrefetchAhead, count - 1)]);
      __builtin_prefetch(&rows_[std::min(row_index + kPrefetchAhead, rows_.size() - 1)], 1);
    }
    Row& row = rows_[row_index];
    // Without isolated contacts every contact is a row, in order: row k is contact k.
    if (find_isolated) row_contact_[row_index] = static_cast<std::uint32_t>(g);
    row.a = BodyRef::particle(c.a);
    row.b = BodyRef::particle(b ? c.b : c.a);
    row.kind = c.kind;
    keepInitialVelocity(c.a, v);
    if (b) keepInitialVelocity(c.b, v);
    const Real wa = inverse_mass[c.a];
    const Real wb = b ? inverse_mass[c.b] : 0.0;
    Real w_sum = wa + wb;
    Vec3 relative_acceleration = wa > 0.0 ? Vec3(acceleration.col(c.a)) : Vec3::Zero();
    Real acceleration_bound = wa > 0.0 ? accelerationNorm(acceleration, c.a) : 0.0;
    if (b && wb > 0.0) {
      relative_acceleration -= acceleration.col(c.b);
      acceleration_bound += accelerationNorm(acceleration, c.b);
    }
    // A link's length change over a substep's move h v from where its ends move from:
    // -h v_sep + the drift of turning, which the row's target takes back (response::turnSpeed).
    std::optional<Real> turn_stretch;
    if (c.kind != ContactKind::kContact) {
      row_turn_[row_index] = 0.0;
      Vec3 normal;
      Real error;
      // The direction where the ends move from (x - beta h v): taken where they are, the row took
      // off the part of v that the link's turn had made radial, every substep (a 5-degree rod
      // pendulum lost 96 % of its swing in 20 s at 60 Hz under semi-implicit Euler).
      if (linkState(c, x, follow_scale_, normal, error)) {
        c.normal = normal;
        Vec3 unused;
        Real ahead = 0.0;
        if (std::abs(error) <= kTurnTolerance * (*links_)[c.link].length &&
            linkState(c, x, follow_scale_ - h, unused, ahead)) {
          turn_stretch = ahead - error;
        }
        // Whether it is taut is told where the ends are (a cable that the last substep left at
        // its length is slack or not by rounding where it moves from).
        Real now = error;
        if (follow_scale_ == h && turn_stretch) {
          now = ahead;
        } else if (follow_scale_ > 0.0 && !linkState(c, x, 0.0, unused, now)) {
          now = error;
        }
        c.penetration = now;
      } else {
        w_sum = 0.0;  // coincident ends: no direction to act along
      }
    }
    row.normal = c.normal;
    row.penetration = c.penetration;
    // Targets are measured on the velocities before any warm start.
    Vec3 relative_velocity = initial_velocity_.col(c.a);
    if (b) relative_velocity -= initial_velocity_.col(c.b);
    const Real v_sep = relative_velocity.dot(c.normal);
    const Real built = std::min(Real{0.0}, relative_acceleration.dot(c.normal) * h);
    // Resting: what is left of the closing speed after removing all the forces built over the
    // substep is below what they can build in two more (explicit Euler moves with the velocity of
    // the step before, so one substep of slack is not enough). Then the target is 0, no bounce.
    const bool resting = response::resting(v_sep - built, acceleration_bound, h);
    // A gap (a contact not yet touching, a cable not yet taut) matters only for slow approaches:
    // it then keeps them from closing faster than the gap allows, so a resting contact or a loaded
    // cable that flickers open does not fall free for a substep and come back with a jolt. A fast
    // approach is let through, to bounce properly in the next substep.
    const bool active = w_sum > 0.0 && c.solvesVelocities() &&
                        !(c.kind != ContactKind::kRod && c.penetration < 0.0 && !resting);
    const bool friction =
        c.kind == ContactKind::kContact && c.friction > 0.0 && c.solvesVelocities();
    row.flags =
        static_cast<std::uint8_t>((b ? Row::kHasB : 0) | (active ? Row::kActive | Row::kSwept : 0) |
                                  (resting ? Row::kResting : 0) | (friction ? Row::kFriction : 0) |
                                  (c.kind != ContactKind::kRod ? Row::kUnilateral : 0) |
                                  (!(w_sum <= 0.0) ? Row::kMovable : 0));
    if (active && !(c.kind == ContactKind::kContact && resting)) {
      // Moves with more than resting contacts' impulses: followed row by row.
      mixed_stamp_[c.a] = stamp_;
      if (b) mixed_stamp_[c.b] = stamp_;
      any_mixed_ = true;
    }
    any_friction_ = any_friction_ || friction;

    row.total = 0.0;
    row.target = 0.0;
    if (friction) {
      friction_coefficient_[row_index] = c.friction;
      friction_total_[row_index].setZero();
    }
    if (!active) continue;
    const Real previous = found >= 0 ? warm_normal_[found] : 0.0;
    // A rod holds either way, at its length: no gap, no bounce.
    if (c.kind != ContactKind::kRod) {
      row.target =
          response::target(resting, c.kind == ContactKind::kContact, v_sep, built, c.penetration,
                           c.restitution, previous, h, follow_scale_ > 0.0, inverse_follow_scale_);
    }
    if (turn_stretch) {
      row_turn_[row_index] = response::turnSpeed(*turn_stretch, v_sep, h);
      row.target += row_turn_[row_index];
    }
    row.total = c.kind == ContactKind::kRod ? previous : std::max(Real{0.0}, previous);
    if (found >= 0 && friction && !warm_friction_.empty()) {
      friction_total_[row_index] =
          response::eigen(response::warmFriction(response::lanes(warm_friction_[found]),
                                                 response::lanes(c.normal), c.friction, row.total));
    }
    // Warm start: each constraint begins with the impulse it ended the last substep with.
    if (row.total == 0.0) continue;
    const Vec3 impulse = friction ? Vec3(row.total * row.normal + friction_total_[row_index])
                                  : Vec3(row.total * row.normal);
    v.col(row.a.particleIndex()) += wa * impulse;
    touch(row.a.particleIndex());
    if (b) {
      v.col(row.b.particleIndex()) -= wb * impulse;
      touch(row.b.particleIndex());
    }
  }
  // The last entries that do not fill four lanes go the scalar way (the same bits).
  const std::size_t whole = batch_count_ - batch_count_ % 4;
  const std::size_t rest = batch_count_ - whole;
  batch_count_ = whole;
  flushIsolatedBatch(contacts, x, v, inverse_mass, acceleration, h, slop);
  for (std::size_t e = whole; e < whole + rest; ++e) {
    const std::uint32_t k = batch_contact_[e];
    const Vec3 previous_friction(batch_previous_friction_[3 * e],
                                 batch_previous_friction_[3 * e + 1],
                                 batch_previous_friction_[3 * e + 2]);
    solveIsolated<false>(base + k, contacts[k], x, v, inverse_mass, acceleration, h, slop,
                         batch_previous_[e], &previous_friction);
  }
  batch_count_ = 0;
  batch_rubs_ = false;
  row_count_ = r;
  warm_cursor_ = cursor;
}

void ContactResolver::flushIsolatedBatch(const std::vector<Contact>& contacts, Vec3Map& x,
                                         Vec3Map& v, const ConstScalarMap& inverse_mass,
                                         const Eigen::Ref<const Vec3Array>& acceleration,
                                         const Real h, const Real slop) {
  if (batch_count_ == 0) return;
  IsolatedBatchInputs in;
  in.contacts = contacts.data();
  in.contact_index = batch_contact_.data();
  in.previous_impulse = batch_previous_.data();
  in.previous_friction = batch_previous_friction_.data();
  in.count = batch_count_;
  in.inverse_mass = inverse_mass.data();
  in.acceleration = acceleration.data();
  in.acceleration_stride = acceleration.outerStride();
  in.h = h;
  in.slop = slop;
  in.follow_scale = follow_scale_;
  in.inverse_follow_scale = inverse_follow_scale_;
  const std::size_t touched_before = touched_.size();
  touched_.resize(touched_before + batch_count_);
  if (batch_rubs_ && next_warm_friction_.empty()) {
    next_warm_friction_.assign(next_warm_key_.size(), Vec3::Zero());
  }
  IsolatedBatchOutputs out;
  out.next_warm_normal = next_warm_normal_.data() + batch_base_;
  out.next_warm_friction =
      next_warm_friction_.empty() ? nullptr : next_warm_friction_[batch_base_].data();
  out.touched = touched_.data() + touched_before;
  out.max_penetration = isolated_max_penetration_;
  out.max_closing = isolated_max_closing_;
  out.corrected = isolated_corrected_;
  solveIsolatedBatch(in, x.data(), v.data(), out);
  touched_.resize(touched_before + out.touched_count);
  isolated_max_penetration_ = out.max_penetration;
  isolated_max_closing_ = out.max_closing;
  isolated_corrected_ = out.corrected;
  any_friction_ = any_friction_ || out.rubbed;
  batch_count_ = 0;
  batch_rubs_ = false;
}

template <bool kBackward, bool kFriction>
Real ContactResolver::velocityPass(Vec3Map& v, const ConstScalarMap& inverse_mass) {
  // One pass of resolveVelocities(), per component in Eigen's order (a dot product is
  // (x + y) + z). Rows come grouped by their first particle (pairs sorted by it within a height
  // layer, collider contacts by particle), and each row's update of v_a is the next row's input:
  // v_a and w_a are kept in registers while the first particle stays the same, off the
  // store-to-load round trip. A row's second particle is never the held one (b != a), so memory
  // is current for it.
  const std::size_t count = row_count_;
  const bool prefetch = count * sizeof(Row) > kStreamingBytes;
  Real* const velocity = v.data();
  const Real* const w = inverse_mass.data();
  Real largest_change = 0.0;
  std::uint32_t held = kNoParticle;
  Real vax = 0.0;
  Real vay = 0.0;
  Real vaz = 0.0;
  Real wa = 0.0;
  for (std::size_t step = 0; step < count; ++step) {
    const std::size_t k = kBackward ? count - 1 - step : step;
    if (prefetch) {
      __builtin_prefetch(&rows_[kBackward ? (k >= kPrefetchAhead ? k - kPrefetchAhead : 0)
                                          : std::min(k + kPrefetchAhead, count - 1)]);
    }
    Row& row = rows_[k];
    if (!(row.flags & Row::kSwept)) continue;
    if (row.a.particleIndex() != held) {
      if (held != kNoParticle) {
        Real* const p = velocity + 3 * std::size_t{held};
        p[0] = vax;
        p[1] = vay;
        p[2] = vaz;
      }
      held = row.a.particleIndex();
      const Real* const p = velocity + 3 * std::size_t{held};
      vax = p[0];
      vay = p[1];
      vaz = p[2];
      wa = w[held];
    }
    const bool b = row.flags & Row::kHasB;
    // As prepare() summed them (an active row's sum is positive).
    const Real wb = b ? w[row.b.particleIndex()] : 0.0;
    const Real w_sum = wa + wb;
    // Depends on the row only, so it is computed ahead of the chain of velocity updates from
    // row to row, which then multiplies instead of dividing.
    const Real effective_mass = 1.0 / w_sum;
    const Real nx = row.normal.x();
    const Real ny = row.normal.y();
    const Real nz = row.normal.z();
    Real* const vb = velocity + 3 * std::size_t{row.b.particleIndex()};
    Real rx = vax;
    Real ry = vay;
    Real rz = vaz;
    if (b) {
      rx -= vb[0];
      ry -= vb[1];
      rz -= vb[2];
    }
    const Real v_sep = (rx * nx + ry * ny) + rz * nz;
    const Real total =
        response::accumulate(row.total, row.target, v_sep, effective_mass, row.unilateral());
    const Real j = total - row.total;
    // Stored only when it changed, so a row that did not act is not written back to memory.
    // A unilateral total is never -0, so j == 0 means the same bits; a rod's is always stored.
    if (j != 0.0 || !row.unilateral()) row.total = total;
    if (j != 0.0) {
      const Real ja = j * wa;
      vax += ja * nx;
      vay += ja * ny;
      vaz += ja * nz;
      if (b) {
        const Real jb = j * wb;
        vb[0] -= jb * nx;
        vb[1] -= jb * ny;
        vb[2] -= jb * nz;
      }
      if (wa > 0.0) touch(row.a.particleIndex());
      if (b && wb > 0.0) touch(row.b.particleIndex());
      largest_change = std::max(largest_change, std::abs(j * w_sum));
    }
    if constexpr (kFriction) {
      if (!(row.flags & Row::kFriction)) continue;
      // Coulomb at the relative velocity the normal impulse left.
      Real sx = vax;
      Real sy = vay;
      Real sz = vaz;
      if (b) {
        sx -= vb[0];
        sy -= vb[1];
        sz -= vb[2];
      }
      const response::Vec<Real> friction = response::coulomb(
          response::lanes(friction_total_[k]), response::Vec<Real>{{sx, sy, sz}},
          response::Vec<Real>{{nx, ny, nz}}, effective_mass, friction_coefficient_[k], total);
      const Vec3 next = response::eigen(friction);
      const Vec3 change = next - friction_total_[k];
      friction_total_[k] = next;
      vax += wa * change.x();
      vay += wa * change.y();
      vaz += wa * change.z();
      if (b) {
        vb[0] -= wb * change.x();
        vb[1] -= wb * change.y();
        vb[2] -= wb * change.z();
      }
      largest_change = std::max(largest_change, change.norm() * w_sum);
    }
  }
  if (held != kNoParticle) {
    Real* const p = velocity + 3 * std::size_t{held};
    p[0] = vax;
    p[1] = vay;
    p[2] = vaz;
  }
  return largest_change;
}

int ContactResolver::resolveVelocities(Vec3Map& v, const ConstScalarMap& inverse_mass,
                                       const CollisionSettings& settings) {
  int passes = 0;
  while (passes < settings.max_iterations) {
    ++passes;
    // Alternate the sweep direction (symmetric Gauss-Seidel): chains converge from both ends.
    const bool backward = passes % 2 == 0;
    Real largest_change = any_friction_ ? (backward ? velocityPass<true, true>(v, inverse_mass)
                                                    : velocityPass<false, true>(v, inverse_mass))
                                        : (backward ? velocityPass<true, false>(v, inverse_mass)
                                                    : velocityPass<false, false>(v, inverse_mass));
    if (!blocks_.empty()) {
      largest_change = std::max(largest_change, solveLinkBlockVelocities(v, inverse_mass));
    }
    if (largest_change <= settings.velocity_tolerance) break;
  }
  return passes;
}

void ContactResolver::followRestingImpulses(Vec3Map& x, const Vec3Map& v,
                                            const ConstScalarMap& inverse_mass) {
  const Real scale = follow_scale_;
  if (scale <= 0.0) return;
  // dx = beta h w J: the move the integrator would have made had the impulses been in the step.
  // A particle whose active rows are all resting contacts changed velocity by exactly those
  // impulses: dx = beta h (v - v_initial). So did one that rests on a contact and is also hit
  // (a grain on the ground struck from above): the impact's push down is what its resting
  // contacts take back, and followed alone they lifted it (6.2 cm at 5 m/s).
  if (any_mixed_) {
    for (std::size_t k = 0; k < row_count_; ++k) {
      const Row& row = rows_[k];
      if (!(row.flags & Row::kActive)) continue;
      // A resting contact that pushes nothing (a gap, a wall beside) holds nothing up.
      if (row.kind == ContactKind::kContact &&
          (!(row.flags & Row::kResting) || !(row.total > 0.0))) {
        continue;
      }
      std::vector<std::uint32_t>& stamp =
          row.kind != ContactKind::kContact ? linked_stamp_ : rests_stamp_;
      stamp[row.a.particleIndex()] = stamp_;
      if (row.flags & Row::kHasB) stamp[row.b.particleIndex()] = stamp_;
    }
  }
  const auto followsAll = [&](const std::uint32_t i) {
    return mixed_stamp_[i] != stamp_ || (rests_stamp_[i] == stamp_ && linked_stamp_[i] != stamp_);
  };
  // None flagged: all are isolated contacts' particles, already followed.
  for (std::size_t t = 0; flagged_count_ > 0 && t < touched_.size(); ++t) {
    const std::uint32_t i = touched_[t];
    // Unflagged: an isolated contact's particle.
    if (!touched_flag_[i] || !followsAll(i)) continue;
    const Vec3 move = scale * (v.col(i) - initial_velocity_.col(i));
    x.col(i) += move;
    displacement_.col(i) += move;
  }
  if (!any_mixed_) return;
  // The others (linked) follow their resting contacts' impulses one by one.
  for (std::size_t k = 0; k < row_count_; ++k) {
    const Row& row = rows_[k];
    if (!(row.flags & Row::kActive) || row.kind != ContactKind::kContact ||
        !(row.flags & Row::kResting)) {
      continue;
    }
    const Vec3 impulse = (row.flags & Row::kFriction)
                             ? Vec3(row.total * row.normal + friction_total_[k])
                             : Vec3(row.total * row.normal);
    if (!followsAll(row.a.particleIndex())) {
      const Vec3 move_a = (scale * inverse_mass[row.a.particleIndex()]) * impulse;
      x.col(row.a.particleIndex()) += move_a;
      displacement_.col(row.a.particleIndex()) += move_a;
    }
    if ((row.flags & Row::kHasB) && !followsAll(row.b.particleIndex())) {
      const Vec3 move_b = (-scale * inverse_mass[row.b.particleIndex()]) * impulse;
      x.col(row.b.particleIndex()) += move_b;
      displacement_.col(row.b.particleIndex()) += move_b;
    }
  }
}

bool ContactResolver::linkCorrection(const Row& row, const Contact& link, const Vec3Map& x,
                                     const CollisionSettings& settings, Vec3& normal,
                                     Real& correction, Real& max_penetration) const {
  Real error;
  if (!linkState(link, x, 0.0, normal, error)) return false;
  max_penetration = std::max(max_penetration, linkOverlap(row, error));
  const Real allowed = settings.rod_tolerance * (*links_)[link.link].length;
  if (row.kind == ContactKind::kCable ? error <= allowed : std::abs(error) <= allowed) {
    return false;
  }
  correction = error;
  return true;
}

int ContactResolver::resolvePositions(const std::vector<Contact>& contacts, Vec3Map& x, Vec3Map& v,
                                      const ConstScalarMap& inverse_mass, const Real h,
                                      const CollisionSettings& settings, ContactStats& stats) {
  const std::size_t count = row_count_;
  const bool prefetch = count * sizeof(Row) > kStreamingBytes;
  const Real slop = settings.penetration_slop;
  // Kept in a register, not in stats (a store and reload on every row), and stored at the end.
  Real max_penetration = stats.max_penetration;
  Real max_closing = 0.0;
  if (!any_friction_) {
    next_warm_friction_.clear();
  } else if (next_warm_friction_.empty()) {
    next_warm_friction_.assign(next_warm_key_.size(), Vec3::Zero());
  }
  for (FedKnot& held : fed_knots_) held.moved.setZero();
  int passes = 0;
  bool corrected = true;
  while (corrected && passes < settings.max_iterations) {
    ++passes;
    corrected = false;
    max_penetration = 0.0;
    const bool backward = passes % 2 == 0;
    for (std::size_t step = 0; step < count; ++step) {
      const std::size_t k = backward ? count - 1 - step : step;
      if (prefetch) {
        __builtin_prefetch(&rows_[backward ? (k >= kPrefetchAhead ? k - kPrefetchAhead : 0)
                                           : std::min(k + kPrefetchAhead, count - 1)]);
      }
      const Row& row = rows_[k];
      const bool b = row.flags & Row::kHasB;
      if (passes == 1) {
        // Velocities and impulses are final: keep the impulses for the next substep (in contact
        // order) and measure the closing speed left.
        const bool keep = (row.flags & Row::kActive) && row.total != 0.0;
        const std::size_t contact = rowContact(k);
        next_warm_normal_[contact] = keep ? row.total : 0.0;
        if (any_friction_) {
          next_warm_friction_[contact] =
              keep && (row.flags & Row::kFriction) ? friction_total_[k] : Vec3(Vec3::Zero());
        }
        if (row.flags & Row::kActive) {
          const Real v_sep = separatingVelocity(row, v);
          // Beyond what the constraint allows: closing at all, or faster than a gap can absorb.
          const Real closing = row.kind == ContactKind::kRod
                                   ? std::abs(v_sep - row.target)
                                   : std::min(Real{0.0}, row.penetration / h) - v_sep;
          max_closing = std::max(max_closing, closing);
        }
      }
      if ((row.flags & (Row::kMovable | Row::kInBlock)) != Row::kMovable) continue;
      Vec3 normal = row.normal;
      Real correction = 0.0;
      if (row.kind == ContactKind::kContact) {
        Vec3 moved = displacement_.col(row.a.particleIndex());
        if (b) moved -= displacement_.col(row.b.particleIndex());
        const Real depth = row.penetration - moved.dot(normal);
        max_penetration = std::max(max_penetration, depth);
        if (depth <= slop) continue;  // a settled pile's rows: no bound to look up
        const Real least = response::leastDepth(
            slop, b ? leastPairDepth(row.a.particleIndex(), row.b.particleIndex(), row.penetration)
                    : -response::kInfinity);
        if (!response::corrects(depth, slop, least)) continue;
        correction = depth - least;
      } else if (!linkCorrection(row, contacts[rowContact(k)], x, settings, normal, correction,
                                 max_penetration)) {
        continue;
      }
      applyCorrection(row, normal, correction, x, inverse_mass);
      corrected = true;
    }
    if (!blocks_.empty()) {
      corrected = correctLinkBlockPositions(contacts, x, inverse_mass, settings, max_penetration) ||
                  corrected;
    }
  }
  if (!fed_knots_.empty()) feedBlockMoves(v, inverse_mass, h);
  stats.max_closing_velocity = max_closing;
  warm_key_.swap(next_warm_key_);
  warm_normal_.swap(next_warm_normal_);
  warm_friction_.swap(next_warm_friction_);
  warm_by_key_.clear();
  if (corrected) {
    // Stopped by max_iterations: measure what the last corrections left.
    max_penetration = 0.0;
    for (std::size_t k = 0; k < count; ++k) {
      const Row& row = rows_[k];
      if (!(row.flags & Row::kMovable)) continue;
      if (row.kind == ContactKind::kContact) {
        Vec3 moved = displacement_.col(row.a.particleIndex());
        if (row.flags & Row::kHasB) moved -= displacement_.col(row.b.particleIndex());
        max_penetration = std::max(max_penetration, row.penetration - moved.dot(row.normal));
      } else {
        Vec3 normal;
        Real error;
        if (!linkState(contacts[rowContact(k)], x, 0.0, normal, error)) continue;
        max_penetration = std::max(max_penetration, linkOverlap(row, error));
      }
    }
  }
  stats.max_penetration = max_penetration;
  return passes;
}

}  // namespace engine
}  // namespace mass_aggregate_sim
