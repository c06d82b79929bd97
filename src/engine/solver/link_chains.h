#pragma once
// Links that form a chain (a rope, a chain of rods, a cable lying partly on the ground), solved as
// one block.
//
// Consecutive rows of a chain share one knot p and no two others share any, so the chain's
//   K = J W J^T,  K_ii = w_a + w_b,  K_i,i+1 = s_i s_i+1 w_p (n_i . n_i+1)
// (s = +1 where p is the row's side a, -1 where it is side b) is tridiagonal, and K dl = r is
// solved exactly in O(m) by its factors K = L D L^T (L unit lower bidiagonal). Gauss-Seidel passes
// carry a load about one link a pass: a hanging rope of 20 rods at 1 substep stayed 14 % stretched,
// one of 200 rods at 4 substeps 105 %.
//
// A chain runs through knots that move (w > 0) and are in exactly two link rows; it ends at an
// anchor, a fixed knot or a knot in one or three or more links (a junction: each chain meeting
// there is a block, and the passes couple the blocks). A closed loop is a chain short of one row,
// which the passes solve alone.

#include <cstdint>
#include <vector>

#include "engine/solver/constraint_row.h"

namespace mass_aggregate_sim {
namespace engine {

class LinkChains {
 public:
  // Finds the chains of two rows or more among the movable link rows of rows[0, count) and flags
  // their rows RowFlags::kChained; `particles` is the number of particles.
  void build(ParticleRow* rows, std::size_t count, const Real* inverse_mass, std::size_t particles);
  void clear();
  bool empty() const { return chain_begin_.size() <= 1; }
  std::size_t size() const { return chain_begin_.size() - 1; }
  std::size_t begin(const std::size_t chain) const { return chain_begin_[chain]; }
  std::size_t end(const std::size_t chain) const { return chain_begin_[chain + 1]; }
  std::size_t entries() const { return row_.size(); }
  // Whether chain c ends at a fixed point (an anchor or a fixed knot) at both of its ends.
  bool heldAtBothEnds(const std::size_t c) const { return held_at_both_ends_[c] != 0; }

  // Entry e (in [begin(c), end(c))): its row, and the knot it shares with the next entry of its
  // chain with s_e s_e+1 (the last entry's are unused).
  std::uint32_t row(const std::size_t e) const { return row_[e]; }
  std::uint32_t sharedKnot(const std::size_t e) const { return shared_[e]; }
  Real sharedSign(const std::size_t e) const { return sign_[e]; }

  // A chain's block, per entry, as the caller fills it: K's diagonal and its coupling with the
  // next entry, the right-hand side, the impulse the entry holds and whether it must stay >= 0
  // (a contact or a cable), and a second right-hand side.
  std::vector<Real> diagonal;
  std::vector<Real> coupling;
  std::vector<Real> rhs;
  std::vector<Real> held;
  std::vector<std::uint8_t> bounded;
  std::vector<Real> second;

  // Factors chain c's K (diagonal, coupling) and keeps the factors; false when K is not
  // positive definite to rounding.
  bool factorKept(std::size_t c);
  // Solves K x = b over chain c's entries with the kept factors, b in place.
  void solveKept(std::size_t c, Real* b) const;
  // K dl = rhs with held + dl >= 0 on the bounded entries, each either strictly inside its bound
  // or at it with (K dl - rhs)_i >= 0 (its constraint satisfied with no impulse): an entry that
  // would cross its bound is held at it (dl = -held, its coupling moved to its neighbours'
  // right-hand sides), one whose constraint its neighbours violate is let go, and the rest solved
  // again. rhs becomes dl; false when a factor fails or the set does not settle.
  bool solveBounded(std::size_t c);

 private:
  void walk(ParticleRow* rows, std::uint32_t first, std::uint32_t entry, const Real* inverse_mass);
  bool through(std::uint32_t knot, const Real* inverse_mass) const;
  void grow();

  std::vector<std::uint32_t> row_;
  std::vector<std::uint32_t> shared_;
  std::vector<Real> sign_;
  std::vector<std::size_t> chain_begin_{0};
  std::vector<std::uint8_t> held_at_both_ends_;  // per chain
  std::vector<Real> pivot_;
  std::vector<Real> lower_;
  std::vector<Real> work_diagonal_;
  std::vector<Real> work_lower_;
  std::vector<Real> work_rhs_;
  std::vector<std::uint8_t> at_bound_;
  // Per particle while building: how many movable link rows it is in, and the first two.
  std::vector<std::uint32_t> degree_;
  std::vector<std::uint32_t> first_;
  std::vector<std::uint32_t> second_;
  std::vector<std::uint8_t> seen_;  // per row while building
  std::vector<std::uint32_t> link_rows_;
};

// K = L D L^T of a symmetric tridiagonal K (diagonal d, off-diagonal e, n entries, e[n - 1]
// unused), in place: d becomes D's pivots and e L's subdiagonal. False when a pivot is not
// positive against its diagonal (K not positive definite to rounding): the caller solves
// otherwise.
bool factorTridiagonal(Real* d, Real* e, std::size_t n);
// Solves L D L^T x = b in place (b becomes x) with factorTridiagonal's d and e.
void solveTridiagonal(const Real* d, const Real* e, Real* b, std::size_t n);

}  // namespace engine
}  // namespace mass_aggregate_sim
