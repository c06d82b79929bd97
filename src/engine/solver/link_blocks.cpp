#include "engine/solver/link_blocks.h"

#include <algorithm>

#include "engine/solver/contact.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

// A pivot below this share of its scale (the least inverse mass of the entry's ends): K is singular
// or nearly (links folded onto one line, or nearly in line between knots that cannot give, as a
// bridge's taut rails), where a Newton step moves knots far for a small error, and the block goes
// row by row. With a pivot down to 1e-12 of the diagonal the shipped bridge's deck gained 54 to
// 95 J of kinetic energy; with this bound it rests at 1.4e-6 J after 40 s (9.4e-6 J when every
// link of it went row by row), at 1e-3 of the least mobility at 2.6e-5 J. The scale is the ends'
// least mobility, not the diagonal, so a light knot holding a heavy one (a mass ratio of 1e6
// leaves a pivot of 1e-6 of the diagonal) is not taken for a singular block.
constexpr Real kLeastPivot = 1e-2;

bool isLink(const ParticleRow& row) {
  return row.kind != ContactKind::kContact && (row.flags & RowFlags::kMovable);
}

std::uint32_t sideB(const ParticleRow& row) {
  return (row.flags & RowFlags::kHasB) ? row.b.particleIndex() : kNoParticle;
}

Real side(const ParticleRow& row, const std::uint32_t knot) {
  return row.a.particleIndex() == knot ? 1.0 : -1.0;
}

bool moving(const std::uint32_t knot, const Real* inverse_mass) {
  return knot != kNoParticle && inverse_mass[knot] > 0.0;
}

}  // namespace

template <typename Visit>
void LinkBlocks::forEachNeighbour(const ParticleRow* rows, const std::uint32_t r,
                                  const Real* inverse_mass, Visit visit) const {
  for (const std::uint32_t knot : {rows[r].a.particleIndex(), sideB(rows[r])}) {
    if (!moving(knot, inverse_mass)) continue;
    for (std::uint32_t n = 0; n < knot_degree_[knot]; ++n) {
      visit(knot_rows_[knot_start_[knot] + n]);
    }
  }
}

std::size_t LinkBlocks::bandEnd() const {
  return band_begin_.empty()
             ? 0
             : band_begin_.back() + (end(size() - 1) - begin(size() - 1)) * bandwidth_.back();
}

void LinkBlocks::clear() {
  row_.clear();
  block_begin_.assign(1, 0);
  bandwidth_.clear();
  band_begin_.clear();
  couplings_.clear();
  coupling_begin_.assign(1, 0);
  knots_.clear();
  knot_begin_.assign(1, 0);
}

void LinkBlocks::build(ParticleRow* rows, const std::size_t count, const Real* inverse_mass,
                       const std::size_t particles) {
  clear();
  if (knot_degree_.size() < particles) {
    knot_degree_.resize(particles, 0);
    knot_start_.resize(particles);
  }
  link_rows_.clear();
  touched_knots_.clear();
  for (std::size_t k = 0; k < count; ++k) {
    if (!isLink(rows[k])) continue;
    link_rows_.push_back(static_cast<std::uint32_t>(k));
    for (const std::uint32_t knot : {rows[k].a.particleIndex(), sideB(rows[k])}) {
      if (moving(knot, inverse_mass) && knot_degree_[knot]++ == 0) touched_knots_.push_back(knot);
    }
  }
  // Each moving knot's rows, in row order.
  std::uint32_t total = 0;
  for (const std::uint32_t knot : touched_knots_) {
    knot_start_[knot] = total;
    total += knot_degree_[knot];
    knot_degree_[knot] = 0;
  }
  knot_rows_.resize(total);
  for (const std::uint32_t r : link_rows_) {
    for (const std::uint32_t knot : {rows[r].a.particleIndex(), sideB(rows[r])}) {
      if (moving(knot, inverse_mass)) knot_rows_[knot_start_[knot] + knot_degree_[knot]++] = r;
    }
  }
  seen_.assign(count, 0);
  place_.assign(count, -1);
  for (const std::uint32_t first : link_rows_) {
    if (seen_[first]) continue;
    component_.assign(1, first);
    seen_[first] = 1;
    for (std::size_t k = 0; k < component_.size(); ++k) {
      forEachNeighbour(rows, component_[k], inverse_mass, [&](const std::uint32_t other) {
        if (seen_[other]) return;
        seen_[other] = 1;
        component_.push_back(other);
      });
    }
    if (component_.size() >= 2) addBlock(rows, inverse_mass);
  }
  for (const std::uint32_t knot : touched_knots_) knot_degree_[knot] = 0;
  const std::size_t n = row_.size();
  for (auto* v : {&diagonal, &least, &rhs, &held, &second, &pivot_, &work_diagonal_, &work_least_,
                  &work_rhs_}) {
    if (v->size() < n) v->resize(n);
  }
  if (bounded.size() < n) {
    bounded.resize(n);
    at_bound_.resize(n);
  }
  const std::size_t band_size = bandEnd();
  for (auto* v : {&band_, &lower_, &work_lower_}) {
    if (v->size() < band_size) v->resize(band_size);
  }
}

bool LinkBlocks::addBlock(ParticleRow* rows, const Real* inverse_mass) {
  // A knot in more links than the band holds makes the band too wide whatever the order.
  for (const std::uint32_t r : component_) {
    for (const std::uint32_t knot : {rows[r].a.particleIndex(), sideB(rows[r])}) {
      if (moving(knot, inverse_mass) && knot_degree_[knot] > kMaxBandwidth + 1) return false;
    }
  }
  // Reverse Cuthill-McKee: a breadth-first order from a row far from the others (the last row
  // reached from the first), reversed.
  const auto breadthFirst = [&](const std::uint32_t start) {
    order_.assign(1, start);
    place_[start] = 0;
    for (std::size_t k = 0; k < order_.size(); ++k) {
      forEachNeighbour(rows, order_[k], inverse_mass, [&](const std::uint32_t other) {
        if (place_[other] >= 0) return;
        place_[other] = static_cast<std::int32_t>(order_.size());
        order_.push_back(other);
      });
    }
    for (const std::uint32_t r : order_) place_[r] = -1;
  };
  breadthFirst(component_.front());
  breadthFirst(order_.back());
  std::reverse(order_.begin(), order_.end());
  const std::size_t base = row_.size();
  for (std::size_t k = 0; k < order_.size(); ++k) {
    place_[order_[k]] = static_cast<std::int32_t>(base + k);
  }
  // Each pair of rows sharing a knot, once per knot (from its first row).
  const std::size_t coupling_base = couplings_.size();
  std::size_t width = 0;
  for (const std::uint32_t r : order_) {
    for (const std::uint32_t knot : {rows[r].a.particleIndex(), sideB(rows[r])}) {
      if (!moving(knot, inverse_mass) || knot_rows_[knot_start_[knot]] != r) continue;
      for (std::uint32_t i = 0; i < knot_degree_[knot]; ++i) {
        for (std::uint32_t j = i + 1; j < knot_degree_[knot]; ++j) {
          const std::uint32_t x = knot_rows_[knot_start_[knot] + i];
          const std::uint32_t y = knot_rows_[knot_start_[knot] + j];
          const auto px = static_cast<std::uint32_t>(place_[x]);
          const auto py = static_cast<std::uint32_t>(place_[y]);
          width = std::max<std::size_t>(width, px > py ? px - py : py - px);
          couplings_.push_back(Coupling{std::min(px, py), std::max(px, py), knot,
                                        side(rows[x], knot) * side(rows[y], knot)});
        }
      }
    }
  }
  for (const std::uint32_t r : order_) place_[r] = -1;
  if (width > kMaxBandwidth) {
    couplings_.resize(coupling_base);
    return false;
  }
  // Its moving knots, each once (from its first row).
  for (const std::uint32_t r : order_) {
    for (const std::uint32_t knot : {rows[r].a.particleIndex(), sideB(rows[r])}) {
      if (moving(knot, inverse_mass) && knot_rows_[knot_start_[knot]] == r) knots_.push_back(knot);
    }
  }
  knot_begin_.push_back(knots_.size());
  const std::size_t band_base = bandEnd();
  for (const std::uint32_t r : order_) {
    row_.push_back(r);
    rows[r].flags =
        static_cast<std::uint8_t>((rows[r].flags | RowFlags::kInBlock) & ~RowFlags::kSwept);
  }
  block_begin_.push_back(row_.size());
  bandwidth_.push_back(width);
  band_begin_.push_back(band_base);
  coupling_begin_.push_back(couplings_.size());
  return true;
}

Real& LinkBlocks::band(std::vector<Real>& values, const std::size_t block, const std::size_t i,
                       const std::size_t k) {
  return values[band_begin_[block] + (i - begin(block)) * bandwidth_[block] + k];
}

Real LinkBlocks::band(const std::vector<Real>& values, const std::size_t block, const std::size_t i,
                      const std::size_t k) const {
  return values[band_begin_[block] + (i - begin(block)) * bandwidth_[block] + k];
}

void LinkBlocks::clearCouplings(const std::size_t block) {
  std::fill_n(&band_[band_begin_[block]], (end(block) - begin(block)) * bandwidth_[block], 0.0);
}

void LinkBlocks::addCoupling(const std::size_t block, const Coupling& coupling, const Real value) {
  band(band_, block, coupling.second, coupling.second - coupling.first - 1) += value;
}

bool LinkBlocks::factor(const std::size_t block, const Real* const diagonal_in,
                        const Real* const least_in, Real* const pivot, std::vector<Real>& lower) {
  // K = L D L^T in place over K's band: L(i, j) = (K(i, j) - sum_k L(i, k) L(j, k) D(k)) / D(j),
  // D(i) = K(i, i) - sum_k L(i, k)^2 D(k), k over the band left of j (of i). Entry i's band
  // holds L(i, i - 1 - k) at l[i w + k].
  const std::size_t s = begin(block);
  const std::size_t n = end(block) - s;
  const std::size_t w = bandwidth_[block];
  Real* const l = lower.data() + band_begin_[block];
  const Real* const diagonal_of = diagonal_in + s;
  const Real* const least_of = least_in + s;
  Real* const d_of = pivot + s;
  if (w == 1) {
    // A chain: L(i, i - 1) = K(i, i - 1) / D(i - 1), D(i) = K(i, i) - L(i, i - 1)^2 D(i - 1).
    for (std::size_t i = 0; i < n; ++i) {
      Real d = diagonal_of[i];
      if (i > 0) {
        l[i] /= d_of[i - 1];
        d -= l[i] * l[i] * d_of[i - 1];
      }
      if (!(d > kLeastPivot * least_of[i])) return false;
      d_of[i] = d;
    }
    return true;
  }
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t low = i > w ? i - w : 0;
    Real* const row_i = l + i * w;
    for (std::size_t j = low; j < i; ++j) {
      const Real* const row_j = l + j * w;
      Real value = row_i[i - j - 1];
      for (std::size_t k = low; k < j; ++k) {
        value -= row_i[i - k - 1] * row_j[j - k - 1] * d_of[k];
      }
      row_i[i - j - 1] = value / d_of[j];
    }
    Real d = diagonal_of[i];
    for (std::size_t k = low; k < i; ++k) {
      const Real lik = row_i[i - k - 1];
      d -= lik * lik * d_of[k];
    }
    if (!(d > kLeastPivot * least_of[i])) return false;
    d_of[i] = d;
  }
  return true;
}

void LinkBlocks::solve(const std::size_t block, const Real* const pivot,
                       const std::vector<Real>& lower, Real* const x) const {
  // L y = b, then D L^T x = y.
  const std::size_t s = begin(block);
  const std::size_t n = end(block) - s;
  const std::size_t w = bandwidth_[block];
  const Real* const l = lower.data() + band_begin_[block];
  if (w == 1) {
    for (std::size_t i = 1; i < n; ++i) x[i] -= l[i] * x[i - 1];
    for (std::size_t i = 0; i < n; ++i) x[i] /= pivot[s + i];
    for (std::size_t i = n - 1; i-- > 0;) x[i] -= l[i + 1] * x[i + 1];
    return;
  }
  for (std::size_t i = 1; i < n; ++i) {
    const Real* const row_i = l + i * w;
    for (std::size_t k = i > w ? i - w : 0; k < i; ++k) x[i] -= row_i[i - k - 1] * x[k];
  }
  for (std::size_t i = 0; i < n; ++i) x[i] /= pivot[s + i];
  for (std::size_t i = n; i-- > 0;) {
    for (std::size_t k = i + 1; k < n && k <= i + w; ++k) x[i] -= l[k * w + k - i - 1] * x[k];
  }
}

bool LinkBlocks::factorKept(const std::size_t block) {
  const std::size_t size = (end(block) - begin(block)) * bandwidth_[block];
  std::copy_n(&band_[band_begin_[block]], size, &lower_[band_begin_[block]]);
  return factor(block, diagonal.data(), least.data(), pivot_.data(), lower_);
}

void LinkBlocks::solveKept(const std::size_t block, Real* const b) const {
  solve(block, pivot_.data(), lower_, b);
}

bool LinkBlocks::solveBounded(const std::size_t block) {
  const std::size_t s = begin(block);
  const std::size_t n = end(block) - s;
  const std::size_t w = bandwidth_[block];
  // K(i, j) over the block's entries (global indices), 0 beyond the band.
  const auto k_of = [&](const std::size_t i, const std::size_t j) -> Real {
    if (i == j) return diagonal[i];
    if (i > j) return i - j <= w ? band(band_, block, i, i - j - 1) : 0.0;
    return j - i <= w ? band(band_, block, j, j - i - 1) : 0.0;
  };
  std::fill_n(&at_bound_[s], n, 0);
  // An active set: an entry that would cross its bound is held at it, and a held entry is let go
  // when its constraint pulls it back in (w_i = (K dl)_i - rhs_i < 0: a cable left at zero
  // impulse would be stretched). Each round changes the set; cycling is cut off.
  for (std::size_t round = 0; round <= 2 * n + 2; ++round) {
    for (std::size_t i = s; i < s + n; ++i) {
      work_diagonal_[i] = at_bound_[i] ? 1.0 : diagonal[i];
      work_least_[i] = at_bound_[i] ? 1.0 : least[i];
      work_rhs_[i] = at_bound_[i] ? -held[i] : rhs[i];
      for (std::size_t k = 0; k < w; ++k) {
        const bool inside = i - s > k;
        band(work_lower_, block, i, k) =
            inside && !at_bound_[i] && !at_bound_[i - k - 1] ? band(band_, block, i, k) : 0.0;
      }
    }
    // A held entry's impulse is known: K_ij dl_j moves to the right-hand side.
    for (std::size_t j = s; j < s + n; ++j) {
      if (!at_bound_[j]) continue;
      const std::size_t low = j - s > w ? j - w : s;
      const std::size_t high = std::min(s + n, j + w + 1);
      for (std::size_t i = low; i < high; ++i) {
        if (i != j && !at_bound_[i]) work_rhs_[i] += k_of(i, j) * held[j];
      }
    }
    if (!factor(block, work_diagonal_.data(), work_least_.data(), work_diagonal_.data(),
                work_lower_)) {
      return false;
    }
    solve(block, work_diagonal_.data(), work_lower_, &work_rhs_[s]);
    bool changed = false;
    for (std::size_t i = s; i < s + n; ++i) {
      if (bounded[i] && !at_bound_[i] && held[i] + work_rhs_[i] < 0.0) {
        at_bound_[i] = 1;
        changed = true;
      }
    }
    for (std::size_t i = s; i < s + n && !changed; ++i) {
      if (!at_bound_[i]) continue;
      const std::size_t low = i - s > w ? i - w : s;
      const std::size_t high = std::min(s + n, i + w + 1);
      Real k_dl = 0.0;
      for (std::size_t j = low; j < high; ++j) k_dl += k_of(i, j) * work_rhs_[j];
      if (k_dl - rhs[i] < 0.0) {
        at_bound_[i] = 0;
        changed = true;
      }
    }
    if (!changed) {
      std::copy_n(&work_rhs_[s], n, &rhs[s]);
      return true;
    }
  }
  return false;
}

}  // namespace engine
}  // namespace mass_aggregate_sim
