#include <algorithm>
#include <cmath>

#include "engine/solver/contact_resolver.h"
#include "engine/solver/contact_response.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

// How many times a block's Newton step is tried (whole, then halved) in a pass before the
// block goes row by row. Whipping at 1 substep for 20 s, a 200-cable rope's worst segment ended
// 47 lengths too long with the whole step alone, 7.8 with three tries; six held a 50-rod rope to
// its lengths but lifted it 2.3 % of m g L above its start (three: 0.4 %), the exact projection
// adding potential energy.
constexpr int kNewtonTries = 3;

}  // namespace

Real ContactResolver::rowMobility(const Row& row, const ConstScalarMap& inverse_mass) const {
  return inverse_mass[row.a.particleIndex()] +
         ((row.flags & Row::kHasB) ? inverse_mass[row.b.particleIndex()] : 0.0);
}

Real ContactResolver::leastMobility(const Row& row, const ConstScalarMap& inverse_mass) const {
  const Real wa = inverse_mass[row.a.particleIndex()];
  const Real wb = (row.flags & Row::kHasB) ? inverse_mass[row.b.particleIndex()] : 0.0;
  return wa > 0.0 && wb > 0.0 ? std::min(wa, wb) : std::max(wa, wb);
}

Real ContactResolver::couplingValue(const LinkBlocks::Coupling& coupling, const Vec3& first,
                                    const Vec3& second, const ConstScalarMap& inverse_mass) const {
  return coupling.sign * inverse_mass[coupling.knot] * first.dot(second);
}

void ContactResolver::prepareLinkBlocks(const ConstScalarMap& inverse_mass,
                                        const Eigen::Ref<const Vec3Array>& acceleration) {
  blocks_.build(rows_.data(), row_count_, inverse_mass.data(),
                static_cast<std::size_t>(inverse_mass.size()));
  if (blocks_.empty()) return;
  if (block_normal_.size() < blocks_.entries()) {
    block_normal_.resize(blocks_.entries());
    block_included_.resize(blocks_.entries());
  }
  block_factored_.assign(blocks_.size(), 0);
  block_newton_.assign(blocks_.size(), 1);
  fed_begin_.assign(blocks_.size(), kNotFed);
  // The velocity phase's rows keep their normals: K is factored once a substep. An inactive row
  // (a slack cable) is out of the block: K_ii = 1, no coupling, no impulse.
  for (std::size_t c = 0; c < blocks_.size(); ++c) {
    for (std::size_t e = blocks_.begin(c); e < blocks_.end(c); ++e) {
      const Row& row = rows_[blocks_.row(e)];
      const bool active = row.flags & Row::kActive;
      blocks_.diagonal[e] = active ? rowMobility(row, inverse_mass) : 1.0;
      blocks_.least[e] = active ? leastMobility(row, inverse_mass) : 1.0;
      blocks_.bounded[e] = active && row.unilateral();
    }
    blocks_.clearCouplings(c);
    for (const LinkBlocks::Coupling* k = blocks_.couplingsBegin(c); k != blocks_.couplingsEnd(c);
         ++k) {
      const Row& first = rows_[blocks_.row(k->first)];
      const Row& second = rows_[blocks_.row(k->second)];
      if ((first.flags & second.flags & Row::kActive) == 0) continue;
      blocks_.addCoupling(c, *k, couplingValue(*k, first.normal, second.normal, inverse_mass));
    }
    // More rows than moving knots (a loop, or fixed at two points or more), or a knot in three
    // links or more: solved as SHAKE solves it.
    const auto knots = static_cast<std::size_t>(blocks_.knotsEnd(c) - blocks_.knotsBegin(c));
    if (blocks_.end(c) - blocks_.begin(c) > knots || blocks_.bandwidth(c) > 1) {
      prepareFedBlock(c, acceleration);
    }
    block_factored_[c] = blocks_.factorKept(c);
    if (block_factored_[c] && fed_begin_[c] == kNotFed) limitBlockTurn(c);
  }
}

void ContactResolver::prepareFedBlock(const std::size_t c,
                                      const Eigen::Ref<const Vec3Array>& acceleration) {
  // Its targets lose their turn parts: the moves of its position corrections, given back as
  // velocity (feedBlockMoves), turn it instead. Projected onto its lengths with no speed taken
  // for it, a 1 kg rope of 20 rods tied between points 0.99 m apart was lifted every substep and
  // gained 2.0 J in 20 s at 1 substep; a Y of three 10-rod arms hung from a point rose 0.39 J.
  fed_begin_[c] = fed_knots_.size();
  for (std::size_t e = blocks_.begin(c); e < blocks_.end(c); ++e) {
    Row& row = rows_[blocks_.row(e)];
    if (row.flags & Row::kActive) row.target -= row_turn_[blocks_.row(e)];
  }
  for (const std::uint32_t* knot = blocks_.knotsBegin(c); knot != blocks_.knotsEnd(c); ++knot) {
    fed_knots_.push_back(
        {*knot, static_cast<std::uint32_t>(c), acceleration.col(*knot), Vec3::Zero()});
  }
}

void ContactResolver::noteFedMoves(const std::size_t c, const Vec3Map& x, const Real sign) {
  for (std::size_t k = fed_begin_[c];
       k < fed_knots_.size() && fed_knots_[k].block == static_cast<std::uint32_t>(c); ++k) {
    fed_knots_[k].moved += sign * x.col(fed_knots_[k].knot);
  }
}

void ContactResolver::feedBlockMoves(Vec3Map& v, const ConstScalarMap& inverse_mass, const Real h) {
  // Each fed block's moves dx become velocity, dv = s dx / h, as SHAKE's positions give theirs
  // (v = (x' - x) / h). The kinetic energy they add, s sum m v.dv + s^2 sum m |dv|^2 / 2, and
  // the potential energy the moves added against the substep's forces, -sum m a.dx, change the
  // block's energy by dE(s); s is the largest in [0, 1] with dE(s) <= 0, or when none, the one
  // that adds the least kinetic energy. Fed whole, a rope tied 0.5 m apart rose 7 mJ above its
  // start, and one laid 50 % short of its lengths (a correction, not a drift) 2.2 J.
  std::size_t first = 0;
  while (first < fed_knots_.size()) {
    const std::uint32_t c = fed_knots_[first].block;
    std::size_t end = first;
    Real linear = 0.0;     // sum m v.dv
    Real quadratic = 0.0;  // sum m |dv|^2 / 2
    Real lifted = 0.0;     // -sum m a.dx
    for (; end < fed_knots_.size() && fed_knots_[end].block == c; ++end) {
      const FedKnot& fed = fed_knots_[end];
      const Real m = 1.0 / inverse_mass[fed.knot];
      const Vec3 dv = fed.moved / h;
      linear += m * v.col(fed.knot).dot(dv);
      quadratic += 0.5 * m * dv.squaredNorm();
      lifted -= m * fed.acceleration.dot(fed.moved);
    }
    Real s = 1.0;
    if (quadratic > 0.0 && linear + quadratic + lifted > 0.0) {
      const Real discriminant = linear * linear - 4.0 * quadratic * lifted;
      const Real root = discriminant >= 0.0
                            ? (-linear + std::sqrt(discriminant)) / (2.0 * quadratic)
                            : -response::kInfinity;
      s = std::clamp(root >= 0.0 ? root : -linear / (2.0 * quadratic), Real{0.0}, Real{1.0});
    }
    for (std::size_t k = first; k < end; ++k) {
      v.col(fed_knots_[k].knot) += (s / h) * fed_knots_[k].moved;
    }
    first = end;
  }
}

void ContactResolver::limitBlockTurn(const std::size_t c) {
  // The impulses the block gives over the phase, from the velocities before any warm start:
  //   l = K^-1 (t - J v) = l0 + K^-1 tau,  l0 = K^-1 (t0 - J v),
  // t0 the targets without their turn parts tau. The kinetic energy they add,
  //   dE = l.(J v) + l.K l / 2 = l.(t + J v) / 2,
  // is dE0 + a l_tau.t0 + a^2 l_tau.tau / 2 with the turn parts scaled by a, where
  // l_tau.tau = tau.K^-1 tau >= 0: every turn part adds. A link alone turns within |v_sep|
  // (response::turnSpeed) and adds nothing; a block's turn parts, each drawn from its own link,
  // added 9 % of a 20-rod rope's drop in its first second at 1 substep. So a is the largest in
  // [0, 1] that adds no energy beyond max(dE0, 0).
  const std::size_t begin = blocks_.begin(c);
  const std::size_t end = blocks_.end(c);
  const auto turn = [&](const std::size_t e) {
    return (rows_[blocks_.row(e)].flags & Row::kActive) ? row_turn_[blocks_.row(e)] : 0.0;
  };
  const auto separating = [&](const std::size_t e) {
    return separatingVelocity(rows_[blocks_.row(e)], initial_velocity_);
  };
  bool turns = false;
  for (std::size_t e = begin; e < end; ++e) {
    const Row& row = rows_[blocks_.row(e)];
    blocks_.second[e] = turn(e);
    blocks_.rhs[e] = (row.flags & Row::kActive) ? row.target - turn(e) - separating(e) : Real{0.0};
    turns = turns || blocks_.second[e] != 0.0;
  }
  if (!turns) return;
  blocks_.solveKept(c, &blocks_.rhs[begin]);
  blocks_.solveKept(c, &blocks_.second[begin]);
  Real gained = 0.0;     // dE0
  Real linear = 0.0;     // l_tau.t0
  Real quadratic = 0.0;  // l_tau.tau / 2
  for (std::size_t e = begin; e < end; ++e) {
    const Row& row = rows_[blocks_.row(e)];
    if (!(row.flags & Row::kActive)) continue;
    const Real t0 = row.target - turn(e);
    gained += 0.5 * blocks_.rhs[e] * (t0 + separating(e));
    linear += blocks_.second[e] * t0;
    quadratic += 0.5 * blocks_.second[e] * turn(e);
  }
  // The largest a in [0, 1] with dE0 + a linear + a^2 quadratic <= max(dE0, 0).
  const Real below = std::min(gained, Real{0.0});
  if (!(quadratic > 0.0) || below + linear + quadratic <= 0.0) return;
  const Real share = std::clamp(
      (-linear + std::sqrt(std::max(Real{0.0}, linear * linear - 4.0 * quadratic * below))) /
          (2.0 * quadratic),
      Real{0.0}, Real{1.0});
  for (std::size_t e = begin; e < end; ++e) {
    rows_[blocks_.row(e)].target -= (1.0 - share) * turn(e);
  }
}

Real ContactResolver::solveRowVelocity(const std::size_t k, Vec3Map& v,
                                       const ConstScalarMap& inverse_mass) {
  Row& row = rows_[k];
  const Real total = response::accumulate(row.total, row.target, separatingVelocity(row, v),
                                          1.0 / rowMobility(row, inverse_mass), row.unilateral());
  const Real j = total - row.total;
  row.total = total;
  return applyRowImpulse(row, j, v, inverse_mass);
}

Real ContactResolver::applyRowImpulse(const Row& row, const Real j, Vec3Map& v,
                                      const ConstScalarMap& inverse_mass) {
  if (j == 0.0) return 0.0;
  const Real wa = inverse_mass[row.a.particleIndex()];
  v.col(row.a.particleIndex()) += (j * wa) * row.normal;
  if (wa > 0.0) touch(row.a.particleIndex());
  if (row.flags & Row::kHasB) {
    const Real wb = inverse_mass[row.b.particleIndex()];
    v.col(row.b.particleIndex()) -= (j * wb) * row.normal;
    if (wb > 0.0) touch(row.b.particleIndex());
  }
  return std::abs(j * rowMobility(row, inverse_mass));
}

Real ContactResolver::solveLinkBlockVelocities(Vec3Map& v, const ConstScalarMap& inverse_mass) {
  Real largest_change = 0.0;
  for (std::size_t c = 0; c < blocks_.size(); ++c) {
    const std::size_t begin = blocks_.begin(c);
    const std::size_t end = blocks_.end(c);
    // K dl = t - J v: every row meets its target at once.
    for (std::size_t e = begin; e < end; ++e) {
      const Row& row = rows_[blocks_.row(e)];
      const bool active = row.flags & Row::kActive;
      blocks_.rhs[e] = active ? row.target - separatingVelocity(row, v) : Real{0.0};
      blocks_.held[e] = row.total;
    }
    // With the factors kept from prepareLinkBlocks while no bound is met, else solved again.
    bool block = block_factored_[c] != 0;
    if (block) {
      std::copy(&blocks_.rhs[begin], &blocks_.rhs[begin] + (end - begin), &blocks_.second[begin]);
      blocks_.solveKept(c, &blocks_.second[begin]);
      for (std::size_t e = begin; e < end && block; ++e) {
        block = !(blocks_.bounded[e] && blocks_.held[e] + blocks_.second[e] < 0.0);
      }
      if (block) {
        std::copy(&blocks_.second[begin], &blocks_.second[begin] + (end - begin),
                  &blocks_.rhs[begin]);
      }
    }
    if (!block) block = blocks_.solveBounded(c);
    for (std::size_t e = begin; e < end; ++e) {
      Row& row = rows_[blocks_.row(e)];
      if (!(row.flags & Row::kActive)) continue;
      if (!block) {
        // K singular or nearly: row by row, as the sweep solves a link in no block.
        largest_change =
            std::max(largest_change, solveRowVelocity(blocks_.row(e), v, inverse_mass));
        continue;
      }
      // A bounded row held at its bound ends at exactly 0.
      const Real total = blocks_.bounded[e] ? std::max(Real{0.0}, row.total + blocks_.rhs[e])
                                            : row.total + blocks_.rhs[e];
      const Real j = total - row.total;
      row.total = total;
      largest_change = std::max(largest_change, applyRowImpulse(row, j, v, inverse_mass));
    }
  }
  return largest_change;
}

Real ContactResolver::blockStrain(const std::size_t e, const std::vector<Contact>& contacts,
                                  const Vec3Map& x, Vec3& normal, Real& error) const {
  const Row& row = rows_[blocks_.row(e)];
  const Contact& link = contacts[rowContact(blocks_.row(e))];
  if (!linkState(link, x, 0.0, normal, error)) return -1.0;
  const Real length = (*links_)[link.link].length;
  return std::max(Real{0.0}, linkOverlap(row, error)) / length;
}

bool ContactResolver::correctLinkBlockPositions(const std::vector<Contact>& contacts, Vec3Map& x,
                                                const ConstScalarMap& inverse_mass,
                                                const CollisionSettings& settings,
                                                Real& max_penetration) {
  bool corrected = false;
  for (std::size_t c = 0; c < blocks_.size(); ++c) {
    const std::size_t begin = blocks_.begin(c);
    const std::size_t end = blocks_.end(c);
    // Where the knots are now: each row's direction and length error, and whether any is beyond
    // its tolerance (then the whole block is brought to its lengths at once).
    bool beyond = false;
    Real worst = 0.0;
    for (std::size_t e = begin; e < end; ++e) {
      const Row& row = rows_[blocks_.row(e)];
      const bool rod = row.kind == ContactKind::kRod;
      Real error = 0.0;
      const Real off = blockStrain(e, contacts, x, block_normal_[e], error);
      // A link with coincident ends is out of the block; a cable is in it, bounded (it only
      // pulls, and one slack enough stays without impulse).
      block_included_[e] = off >= 0.0;
      blocks_.rhs[e] = block_included_[e] ? error : 0.0;
      blocks_.held[e] = 0.0;
      blocks_.bounded[e] = block_included_[e] && !rod;
      blocks_.diagonal[e] = block_included_[e] ? rowMobility(row, inverse_mass) : 1.0;
      blocks_.least[e] = block_included_[e] ? leastMobility(row, inverse_mass) : 1.0;
      if (off < 0.0) continue;
      max_penetration = std::max(max_penetration, linkOverlap(row, error));
      beyond = beyond || off > settings.rod_tolerance;
      worst = std::max(worst, off);
    }
    if (!beyond) continue;
    corrected = true;
    const bool held = fed_begin_[c] != kNotFed;
    if (held) noteFedMoves(c, x, -1.0);
    correctLinkBlock(c, contacts, x, inverse_mass, settings, worst, max_penetration);
    if (held) noteFedMoves(c, x, 1.0);
  }
  return corrected;
}

void ContactResolver::correctLinkBlock(const std::size_t c, const std::vector<Contact>& contacts,
                                       Vec3Map& x, const ConstScalarMap& inverse_mass,
                                       const CollisionSettings& settings, const Real worst,
                                       Real& max_penetration) {
  const std::size_t begin = blocks_.begin(c);
  const std::size_t end = blocks_.end(c);
  // K dl = C: the length change of row i is -(K dl)_i to first order, where the ends move by
  // dx_a = w_a dl n, dx_b = -w_b dl n; a cable only pulls (dl >= 0).
  blocks_.clearCouplings(c);
  for (const LinkBlocks::Coupling* k = blocks_.couplingsBegin(c); k != blocks_.couplingsEnd(c);
       ++k) {
    if (!block_included_[k->first] || !block_included_[k->second]) continue;
    blocks_.addCoupling(
        c, *k, couplingValue(*k, block_normal_[k->first], block_normal_[k->second], inverse_mass));
  }
  if (block_newton_[c] && blocks_.solveBounded(c)) {
    // One Newton step on the lengths, along the directions the links have now: exact to first
    // order, and far off where links are stretched and bent (a 50-rod rope 30 % stretched in a
    // zigzag went to 100 %). Kept, whole, halved or quartered, only when it leaves the block's
    // worst strain lower; refused, the block goes row by row for the rest of the substep (a
    // 200-rod rope whipping at 4 substeps, refused on most passes, cost 3.4 times as much as
    // row by row trying on every pass, 1.6 times so, with the same worst stretch).
    saveBlockKnots(c, x);
    bool lowered = false;
    Real scale = 1.0;
    for (int attempt = 0; attempt < kNewtonTries && !lowered; ++attempt, scale *= 0.5) {
      if (attempt > 0) restoreBlockKnots(c, x);
      applyLinkBlockPositions(c, scale, x, inverse_mass);
      Real after = 0.0;
      for (std::size_t e = begin; e < end; ++e) {
        Vec3 normal;
        Real error;
        after = std::max(after, blockStrain(e, contacts, x, normal, error));
      }
      lowered = after < worst;
    }
    if (lowered) return;
    restoreBlockKnots(c, x);
    block_newton_[c] = 0;
  }
  // Row by row, as the sweep corrects a link that is in no block.
  for (std::size_t e = begin; e < end; ++e) {
    const Row& row = rows_[blocks_.row(e)];
    Vec3 normal;
    Real correction = 0.0;
    if (linkCorrection(row, contacts[rowContact(blocks_.row(e))], x, settings, normal, correction,
                       max_penetration)) {
      applyCorrection(row, normal, correction, x, inverse_mass);
    }
  }
}

void ContactResolver::applyLinkBlockPositions(const std::size_t c, const Real scale, Vec3Map& x,
                                              const ConstScalarMap& inverse_mass) {
  // dx_a = w_a dl n, dx_b = -w_b dl n: a correction of dl (w_a + w_b) along n.
  for (std::size_t e = blocks_.begin(c); e < blocks_.end(c); ++e) {
    if (!block_included_[e] || blocks_.rhs[e] == 0.0) continue;
    const Row& row = rows_[blocks_.row(e)];
    applyCorrection(row, block_normal_[e], scale * blocks_.rhs[e] * rowMobility(row, inverse_mass),
                    x, inverse_mass);
  }
}

void ContactResolver::saveBlockKnots(const std::size_t c, const Vec3Map& x) {
  block_saved_.clear();
  for (std::size_t e = blocks_.begin(c); e < blocks_.end(c); ++e) {
    const Row& row = rows_[blocks_.row(e)];
    for (const std::uint32_t i : {row.a.particleIndex(), row.b.particleIndex()}) {
      block_saved_.push_back(x.col(i));
      block_saved_.push_back(displacement_.col(i));
    }
  }
}

void ContactResolver::restoreBlockKnots(const std::size_t c, Vec3Map& x) {
  // Every copy of a knot was taken before any move: restored in any order, it is as it was.
  std::size_t k = 0;
  for (std::size_t e = blocks_.begin(c); e < blocks_.end(c); ++e) {
    const Row& row = rows_[blocks_.row(e)];
    for (const std::uint32_t i : {row.a.particleIndex(), row.b.particleIndex()}) {
      x.col(i) = block_saved_[k++];
      displacement_.col(i) = block_saved_[k++];
    }
  }
}

}  // namespace engine
}  // namespace mass_aggregate_sim
