#include "engine/solver/link_chains.h"

#include <algorithm>

#include "engine/solver/contact.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

// A pivot below this share of its diagonal: K is singular to rounding (links folded onto one
// line through a knot that cannot take both).
constexpr Real kLeastPivot = 1e-12;

bool isLink(const ParticleRow& row) {
  return row.kind != ContactKind::kContact && (row.flags & RowFlags::kMovable);
}

std::uint32_t sideB(const ParticleRow& row) {
  return (row.flags & RowFlags::kHasB) ? row.b.particleIndex() : kNoParticle;
}

// The row's end that is not `knot` (kNoParticle for an anchor).
std::uint32_t otherEnd(const ParticleRow& row, const std::uint32_t knot) {
  return row.a.particleIndex() == knot ? sideB(row) : row.a.particleIndex();
}

Real side(const ParticleRow& row, const std::uint32_t knot) {
  return row.a.particleIndex() == knot ? 1.0 : -1.0;
}

}  // namespace

bool LinkChains::through(const std::uint32_t knot, const Real* inverse_mass) const {
  return knot != kNoParticle && inverse_mass[knot] > 0.0 && degree_[knot] == 2;
}

void LinkChains::clear() {
  row_.clear();
  shared_.clear();
  sign_.clear();
  chain_begin_.assign(1, 0);
  held_at_both_ends_.clear();
}

void LinkChains::build(ParticleRow* rows, const std::size_t count, const Real* inverse_mass,
                       const std::size_t particles) {
  clear();
  if (degree_.size() < particles) {
    degree_.resize(particles, 0);
    first_.resize(particles);
    second_.resize(particles);
  }
  link_rows_.clear();
  for (std::size_t k = 0; k < count; ++k) {
    if (!isLink(rows[k])) continue;
    const auto r = static_cast<std::uint32_t>(k);
    link_rows_.push_back(r);
    for (const std::uint32_t knot : {rows[k].a.particleIndex(), sideB(rows[k])}) {
      if (knot == kNoParticle || !(inverse_mass[knot] > 0.0)) continue;
      const std::uint32_t d = degree_[knot]++;
      if (d == 0) first_[knot] = r;
      if (d == 1) second_[knot] = r;
    }
  }
  seen_.assign(count, 0);
  // From the chains' ends first; what is left is in closed loops.
  for (const std::uint32_t r : link_rows_) {
    if (seen_[r]) continue;
    const std::uint32_t a = rows[r].a.particleIndex();
    const std::uint32_t b = sideB(rows[r]);
    if (!through(a, inverse_mass)) {
      walk(rows, r, a, inverse_mass);
    } else if (!through(b, inverse_mass)) {
      walk(rows, r, b, inverse_mass);
    }
  }
  for (const std::uint32_t r : link_rows_) {
    if (!seen_[r]) walk(rows, r, rows[r].a.particleIndex(), inverse_mass);
  }
  for (const std::uint32_t r : link_rows_) {
    for (const std::uint32_t knot : {rows[r].a.particleIndex(), sideB(rows[r])}) {
      if (knot != kNoParticle) degree_[knot] = 0;
    }
  }
  grow();
}

void LinkChains::walk(ParticleRow* rows, std::uint32_t first, const std::uint32_t entry,
                      const Real* inverse_mass) {
  const std::size_t start = row_.size();
  std::uint32_t r = first;
  std::uint32_t knot = otherEnd(rows[r], entry);
  seen_[r] = 1;
  row_.push_back(r);
  shared_.push_back(kNoParticle);
  sign_.push_back(0.0);
  while (through(knot, inverse_mass)) {
    const std::uint32_t next = first_[knot] == r ? second_[knot] : first_[knot];
    const std::uint32_t beyond = otherEnd(rows[next], knot);
    // A loop closing on the chain's first knot: its last row is left to the passes, so no two
    // rows but neighbours share a knot.
    if (seen_[next] || (beyond != kNoParticle && beyond == entry)) break;
    shared_.back() = knot;
    sign_.back() = side(rows[r], knot) * side(rows[next], knot);
    seen_[next] = 1;
    row_.push_back(next);
    shared_.push_back(kNoParticle);
    sign_.push_back(0.0);
    r = next;
    knot = beyond;
  }
  if (row_.size() - start < 2) {
    row_.resize(start);
    shared_.resize(start);
    sign_.resize(start);
    return;
  }
  for (std::size_t e = start; e < row_.size(); ++e) {
    ParticleRow& row = rows[row_[e]];
    row.flags = static_cast<std::uint8_t>((row.flags | RowFlags::kChained) & ~RowFlags::kSwept);
  }
  const auto fixed = [inverse_mass](const std::uint32_t end) {
    return end == kNoParticle || !(inverse_mass[end] > 0.0);
  };
  held_at_both_ends_.push_back(fixed(entry) && fixed(knot));
  chain_begin_.push_back(row_.size());
}

void LinkChains::grow() {
  const std::size_t n = row_.size();
  if (diagonal.size() >= n) return;
  for (auto* v : {&diagonal, &coupling, &rhs, &held, &second, &pivot_, &lower_, &work_diagonal_,
                  &work_lower_, &work_rhs_}) {
    v->resize(n);
  }
  bounded.resize(n);
  at_bound_.resize(n);
}

bool LinkChains::factorKept(const std::size_t c) {
  const std::size_t b = begin(c);
  const std::size_t n = end(c) - b;
  std::copy_n(&diagonal[b], n, &pivot_[b]);
  std::copy_n(&coupling[b], n, &lower_[b]);
  return factorTridiagonal(&pivot_[b], &lower_[b], n);
}

void LinkChains::solveKept(const std::size_t c, Real* const x) const {
  solveTridiagonal(&pivot_[begin(c)], &lower_[begin(c)], x, end(c) - begin(c));
}

bool LinkChains::solveBounded(const std::size_t c) {
  const std::size_t b = begin(c);
  const std::size_t n = end(c) - b;
  std::fill_n(&at_bound_[b], n, 0);
  // An active set: an entry that would cross its bound is held at it, and a held entry is let go
  // when its constraint pulls it back in (w_i = (K dl)_i - rhs_i < 0: a contact or cable left at
  // zero impulse would be violated). Each round changes the set; cycling is cut off.
  for (std::size_t round = 0; round <= 2 * n + 2; ++round) {
    for (std::size_t i = b; i < b + n; ++i) {
      const bool first = i == b;
      const bool last = i + 1 == b + n;
      if (at_bound_[i]) {
        work_diagonal_[i] = 1.0;
        work_rhs_[i] = -held[i];
      } else {
        work_diagonal_[i] = diagonal[i];
        work_rhs_[i] = rhs[i];
        // A held neighbour's impulse is known: K_ij dl_j moves to the right-hand side.
        if (!first && at_bound_[i - 1]) work_rhs_[i] += coupling[i - 1] * held[i - 1];
        if (!last && at_bound_[i + 1]) work_rhs_[i] += coupling[i] * held[i + 1];
      }
      work_lower_[i] = !last && !at_bound_[i] && !at_bound_[i + 1] ? coupling[i] : 0.0;
    }
    if (!factorTridiagonal(&work_diagonal_[b], &work_lower_[b], n)) return false;
    solveTridiagonal(&work_diagonal_[b], &work_lower_[b], &work_rhs_[b], n);
    bool changed = false;
    for (std::size_t i = b; i < b + n; ++i) {
      if (bounded[i] && !at_bound_[i] && held[i] + work_rhs_[i] < 0.0) {
        at_bound_[i] = 1;
        changed = true;
      }
    }
    for (std::size_t i = b; i < b + n && !changed; ++i) {
      if (!at_bound_[i]) continue;
      Real k_dl = diagonal[i] * work_rhs_[i];
      if (i > b) k_dl += coupling[i - 1] * work_rhs_[i - 1];
      if (i + 1 < b + n) k_dl += coupling[i] * work_rhs_[i + 1];
      if (k_dl - rhs[i] < 0.0) {
        at_bound_[i] = 0;
        changed = true;
      }
    }
    if (!changed) {
      std::copy_n(&work_rhs_[b], n, &rhs[b]);
      return true;
    }
  }
  return false;
}

bool factorTridiagonal(Real* const d, Real* const e, const std::size_t n) {
  // K_ii = D_i + l_i-1^2 D_i-1,  K_i,i+1 = l_i D_i.
  for (std::size_t i = 0; i < n; ++i) {
    const Real diagonal = d[i];
    if (i > 0) d[i] -= e[i - 1] * e[i - 1] * d[i - 1];
    if (!(d[i] > kLeastPivot * diagonal)) return false;
    if (i + 1 < n) e[i] /= d[i];
  }
  return true;
}

void solveTridiagonal(const Real* const d, const Real* const e, Real* const b,
                      const std::size_t n) {
  // L y = b, then D L^T x = y.
  for (std::size_t i = 1; i < n; ++i) b[i] -= e[i - 1] * b[i - 1];
  b[n - 1] /= d[n - 1];
  for (std::size_t i = n - 1; i-- > 0;) b[i] = b[i] / d[i] - e[i] * b[i + 1];
}

}  // namespace engine
}  // namespace mass_aggregate_sim
