#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "mass_aggregate_sim/engine/collision/collision_settings.h"
#include "mass_aggregate_sim/engine/core/types.h"

namespace mass_aggregate_sim {
namespace engine {

struct IndexPair {
  std::uint32_t a;  // a < b
  std::uint32_t b;
  friend bool operator==(const IndexPair& x, const IndexPair& y) {
    return x.a == y.a && x.b == y.b;
  }
  friend bool operator<(const IndexPair& x, const IndexPair& y) {
    return x.a != y.a ? x.a < y.a : x.b < y.b;
  }
};

// True when the closed boxes [lo_i, hi_i] and [lo_j, hi_j] overlap.
inline bool boxesOverlap(const Vec3Array& lo, const Vec3Array& hi, const Eigen::Index i,
                         const Eigen::Index j) {
  return lo(0, i) <= hi(0, j) && lo(0, j) <= hi(0, i) && lo(1, i) <= hi(1, j) &&
         lo(1, j) <= hi(1, i) && lo(2, i) <= hi(2, j) && lo(2, j) <= hi(2, i);
}

// Finds every pair i < j of overlapping axis-aligned boxes, each pair once, in a deterministic
// order. Boxes with a non-finite corner take part in no pair. Keeps its buffers between calls.
class BroadphaseFinder {
 public:
  void findPairs(Broadphase method, const Vec3Array& lo, const Vec3Array& hi,
                 std::vector<IndexPair>& pairs);

 private:
  struct SweepEntry {
    Real lo;
    Real hi;
    std::uint32_t index;
  };
  struct CellEntry {
    std::int64_t cell[3];
    std::uint32_t bucket;
    std::uint32_t index;
  };
  void sortAndSweep(const Vec3Array& lo, const Vec3Array& hi, std::vector<IndexPair>& pairs);
  void uniformGrid(const Vec3Array& lo, const Vec3Array& hi, std::vector<IndexPair>& pairs);
  // Boxes of similar size packed in a compact region: a dense table of cells `largest` across,
  // each box in the cell of its low corner, each cell against its neighbours. False (nothing
  // done) when the table would be too large for the number of boxes.
  bool denseGrid(const Vec3Array& lo, const Vec3Array& hi, Real largest,
                 std::vector<IndexPair>& pairs);

  std::vector<SweepEntry> sweep_;
  std::vector<CellEntry> entries_;
  std::vector<CellEntry> sorted_entries_;
  std::vector<std::uint32_t> bucket_start_;
  std::vector<std::uint32_t> oversize_;
  std::vector<Real> extents_;
  std::vector<std::uint32_t> bucket_cursor_;
  std::vector<std::uint32_t> cell_start_;
  std::vector<std::uint32_t> box_cell_;
  std::vector<std::uint32_t> cell_boxes_;
  using Box = std::array<Real, 6>;  // lo x, y, z, hi x, y, z
  std::vector<Box> sorted_boxes_;
};

// The O(N^2) reference: every overlapping pair, tested one by one. For tests only.
void bruteForcePairs(const Vec3Array& lo, const Vec3Array& hi, std::vector<IndexPair>& pairs);

}  // namespace engine
}  // namespace mass_aggregate_sim
