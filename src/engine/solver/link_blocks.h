#pragma once
// Links that hang together (a rope, a chain of rods, a net, a bridge's deck and hangers), solved
// as one block.
//
// The link rows that share moving knots form a block whose
//   K = J W J^T,  K_ii = w_a + w_b,  K_ij = sum over the knots p i and j share of s_i s_j w_p
//   n_i.n_j
// (s = +1 where p is the row's side a, -1 where it is side b) is sparse. Ordered by reverse
// Cuthill-McKee, a chain's K is tridiagonal and a ladder's or a bridge deck's has a band a few
// rows wide: K dl = r is solved exactly in O(m w^2) by its banded factors K = L D L^T.
// Gauss-Seidel passes carry a load about one link a pass: a hanging rope of 20 rods at 1 substep
// stayed 14 % stretched, one of 200 rods at 4 substeps 105 %.
//
// A block ends at anchors and fixed knots (w = 0), which couple nothing. One whose band would be
// wider than kMaxBandwidth (a knot in many links, a wide net) is left to the passes, row by row.

#include <cstdint>
#include <vector>

#include "engine/solver/constraint_row.h"

namespace mass_aggregate_sim {
namespace engine {

class LinkBlocks {
 public:
  static constexpr std::size_t kMaxBandwidth = 16;

  // Two entries of a block that share a knot: first < second, and s_first s_second there.
  struct Coupling {
    std::uint32_t first;
    std::uint32_t second;
    std::uint32_t knot;
    Real sign;
  };

  // Finds the blocks of two rows or more among the movable link rows of rows[0, count) and flags
  // their rows RowFlags::kInBlock; `particles` is the number of particles.
  void build(ParticleRow* rows, std::size_t count, const Real* inverse_mass, std::size_t particles);
  void clear();
  bool empty() const { return block_begin_.size() <= 1; }
  std::size_t size() const { return block_begin_.size() - 1; }
  std::size_t begin(const std::size_t block) const { return block_begin_[block]; }
  std::size_t end(const std::size_t block) const { return block_begin_[block + 1]; }
  std::size_t entries() const { return row_.size(); }
  std::uint32_t row(const std::size_t e) const { return row_[e]; }
  std::size_t bandwidth(const std::size_t block) const { return bandwidth_[block]; }
  // The block's moving knots, each once.
  const std::uint32_t* knotsBegin(const std::size_t block) const {
    return knots_.data() + knot_begin_[block];
  }
  const std::uint32_t* knotsEnd(const std::size_t block) const {
    return knots_.data() + knot_begin_[block + 1];
  }
  const Coupling* couplingsBegin(const std::size_t block) const {
    return couplings_.data() + coupling_begin_[block];
  }
  const Coupling* couplingsEnd(const std::size_t block) const {
    return couplings_.data() + coupling_begin_[block + 1];
  }

  // A block's system, per entry as the caller fills it: K's diagonal and its pivots' scale, the
  // right-hand side, the
  // impulse the entry holds and whether it must stay >= 0 (a cable), and a second right-hand
  // side; K's couplings through clearCouplings and addCoupling.
  std::vector<Real> diagonal;
  std::vector<Real>
      least;  // the least positive inverse mass of the entry's ends: its pivot's scale
  std::vector<Real> rhs;
  std::vector<Real> held;
  std::vector<std::uint8_t> bounded;
  std::vector<Real> second;
  void clearCouplings(std::size_t block);
  void addCoupling(std::size_t block, const Coupling& coupling, Real value);

  // Factors the block's K and keeps the factors; false when K is not positive definite to
  // rounding.
  bool factorKept(std::size_t block);
  // Solves K x = b over the block's entries with the kept factors, b in place.
  void solveKept(std::size_t block, Real* b) const;
  // K dl = rhs with held + dl >= 0 on the bounded entries, each either strictly inside its bound
  // or at it with (K dl - rhs)_i >= 0 (its constraint satisfied with no impulse): an entry that
  // would cross its bound is held at it (dl = -held, its couplings moved to the right-hand side),
  // one whose constraint the others violate is let go, and the rest solved again. rhs becomes dl;
  // false when a factor fails or the set does not settle.
  bool solveBounded(std::size_t block);

 private:
  // K's strictly lower band: entry i's K(i, i - 1 - k) at band_[band_begin_ + (i - begin) w + k].
  Real& band(std::vector<Real>& band, std::size_t block, std::size_t i, std::size_t k);
  Real band(const std::vector<Real>& band, std::size_t block, std::size_t i, std::size_t k) const;
  bool factor(std::size_t block, const Real* diagonal, const Real* least, Real* pivot,
              std::vector<Real>& lower);
  void solve(std::size_t block, const Real* pivot, const std::vector<Real>& lower, Real* x) const;
  bool addBlock(ParticleRow* rows, const Real* inverse_mass);
  // Calls visit(other) for every link row that shares a moving knot with row r (r among them),
  // from the knots' row lists that build() makes.
  template <typename Visit>
  void forEachNeighbour(const ParticleRow* rows, std::uint32_t r, const Real* inverse_mass,
                        Visit visit) const;
  // Where the next block's band starts.
  std::size_t bandEnd() const;

  std::vector<std::uint32_t> row_;
  std::vector<std::size_t> block_begin_{0};
  std::vector<std::size_t> bandwidth_;
  std::vector<std::size_t> band_begin_;
  std::vector<Coupling> couplings_;
  std::vector<std::size_t> coupling_begin_{0};
  std::vector<std::uint32_t> knots_;
  std::vector<std::size_t> knot_begin_{0};
  std::vector<Real> band_;
  std::vector<Real> pivot_;
  std::vector<Real> lower_;
  std::vector<Real> work_diagonal_;
  std::vector<Real> work_least_;
  std::vector<Real> work_lower_;
  std::vector<Real> work_rhs_;
  std::vector<std::uint8_t> at_bound_;
  // While building: each moving knot's link rows (CSR), each row's block order, the component.
  std::vector<std::uint32_t> knot_degree_;
  std::vector<std::uint32_t> knot_start_;
  std::vector<std::uint32_t> knot_rows_;
  std::vector<std::uint32_t> touched_knots_;
  std::vector<std::int32_t> place_;  // per row: its entry in the block being built, or -1
  std::vector<std::uint8_t> seen_;   // per row
  std::vector<std::uint32_t> link_rows_;
  std::vector<std::uint32_t> component_;
  std::vector<std::uint32_t> order_;
};

}  // namespace engine
}  // namespace mass_aggregate_sim
