#include "engine/collision/broadphase.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace mass_aggregate_sim {
namespace engine {
namespace {

// A box covering more cells than this is tested against every other box instead of being hashed.
constexpr std::int64_t kMaxCellsPerBox = 64;
// Boxes at most this many times the median size use the dense grid of cells one widest box across,
// when its table has at most kDenseCellsPerBox cells per box.
constexpr Real kMaxDenseSizeRatio = 2.0;
constexpr Real kDenseCellsPerBox = 4.0;
constexpr std::uint32_t kNoCell = 0xFFFFFFFFu;

bool finiteBox(const Vec3Array& lo, const Vec3Array& hi, const Eigen::Index i) {
  return lo.col(i).allFinite() && hi.col(i).allFinite();
}

IndexPair ordered(const std::uint32_t i, const std::uint32_t j) {
  return i < j ? IndexPair{i, j} : IndexPair{j, i};
}

std::uint32_t hashCell(const std::int64_t x, const std::int64_t y, const std::int64_t z) {
  // Large odd multipliers spread neighbouring cells over the table.
  const auto h = static_cast<std::uint64_t>(x) * 0x9E3779B185EBCA87ull ^
                 static_cast<std::uint64_t>(y) * 0xC2B2AE3D27D4EB4Full ^
                 static_cast<std::uint64_t>(z) * 0x165667B19E3779F9ull;
  return static_cast<std::uint32_t>(h ^ (h >> 29));
}

}  // namespace

void BroadphaseFinder::findPairs(const Broadphase method, const Vec3Array& lo, const Vec3Array& hi,
                                 std::vector<IndexPair>& pairs) {
  pairs.clear();
  if (lo.cols() < 2) return;
  switch (method) {
    case Broadphase::kSortAndSweep:
      sortAndSweep(lo, hi, pairs);
      break;
    case Broadphase::kUniformGrid:
      uniformGrid(lo, hi, pairs);
      break;
  }
}

void BroadphaseFinder::sortAndSweep(const Vec3Array& lo, const Vec3Array& hi,
                                    std::vector<IndexPair>& pairs) {
  const Eigen::Index n = lo.cols();
  // Sweep along the axis where the box centres are spread the most: fewest overlapping intervals.
  Vec3 mean = Vec3::Zero();
  Vec3 mean_square = Vec3::Zero();
  Eigen::Index finite_count = 0;
  for (Eigen::Index i = 0; i < n; ++i) {
    if (!finiteBox(lo, hi, i)) continue;
    const Vec3 centre = 0.5 * (lo.col(i) + hi.col(i));
    mean += centre;
    mean_square += centre.cwiseProduct(centre);
    ++finite_count;
  }
  if (finite_count < 2) return;
  mean /= static_cast<Real>(finite_count);
  mean_square /= static_cast<Real>(finite_count);
  Eigen::Index axis = 0;
  (mean_square - mean.cwiseProduct(mean)).maxCoeff(&axis);

  sweep_.clear();
  for (Eigen::Index i = 0; i < n; ++i) {
    if (finiteBox(lo, hi, i)) {
      sweep_.push_back({lo(axis, i), hi(axis, i), static_cast<std::uint32_t>(i)});
    }
  }
  std::sort(sweep_.begin(), sweep_.end(), [](const SweepEntry& x, const SweepEntry& y) {
    return x.lo != y.lo ? x.lo < y.lo : x.index < y.index;
  });
  const std::size_t count = sweep_.size();
  for (std::size_t s = 0; s < count; ++s) {
    const SweepEntry& current = sweep_[s];
    for (std::size_t t = s + 1; t < count && sweep_[t].lo <= current.hi; ++t) {
      const std::uint32_t other = sweep_[t].index;
      if (boxesOverlap(lo, hi, current.index, other))
        pairs.push_back(ordered(current.index, other));
    }
  }
}

void BroadphaseFinder::uniformGrid(const Vec3Array& lo, const Vec3Array& hi,
                                   std::vector<IndexPair>& pairs) {
  const Eigen::Index n = lo.cols();
  // Cell edge: the median box size, so a typical box covers at most 2 cells per axis and a few
  // large or fast ones do not make every cell large.
  extents_.clear();
  for (Eigen::Index i = 0; i < n; ++i) {
    if (finiteBox(lo, hi, i)) extents_.push_back((hi.col(i) - lo.col(i)).maxCoeff());
  }
  if (extents_.size() < 2) return;
  const Real largest = *std::max_element(extents_.begin(), extents_.end());
  const auto middle = extents_.begin() + static_cast<std::ptrdiff_t>(extents_.size() / 2);
  std::nth_element(extents_.begin(), middle, extents_.end());
  if (largest <= kMaxDenseSizeRatio * *middle && denseGrid(lo, hi, largest, pairs)) return;
  Real cell = *middle;
  if (!(cell > 0.0)) cell = *std::max_element(extents_.begin(), extents_.end());
  if (!(cell > 0.0)) cell = 1.0;
  const Real inverse_cell = 1.0 / cell;

  entries_.clear();
  oversize_.clear();
  Eigen::Matrix<std::int64_t, 3, 1> first;
  Eigen::Matrix<std::int64_t, 3, 1> last;
  for (Eigen::Index i = 0; i < n; ++i) {
    if (!finiteBox(lo, hi, i)) continue;
    bool too_big = false;
    for (int k = 0; k < 3; ++k) {
      const Real a = std::floor(lo(k, i) * inverse_cell);
      const Real b = std::floor(hi(k, i) * inverse_cell);
      // Beyond +-2^52 cells the coordinates lose integer precision: treat as oversize.
      if (!(std::abs(a) < 4.5e15 && std::abs(b) < 4.5e15) || b - a >= kMaxCellsPerBox) {
        too_big = true;
        break;
      }
      first[k] = static_cast<std::int64_t>(a);
      last[k] = static_cast<std::int64_t>(b);
    }
    const std::int64_t cells =
        too_big ? 0 : (last - first + Eigen::Matrix<std::int64_t, 3, 1>::Ones()).prod();
    if (too_big || cells > kMaxCellsPerBox) {
      oversize_.push_back(static_cast<std::uint32_t>(i));
      continue;
    }
    for (std::int64_t x = first[0]; x <= last[0]; ++x) {
      for (std::int64_t y = first[1]; y <= last[1]; ++y) {
        for (std::int64_t z = first[2]; z <= last[2]; ++z) {
          entries_.push_back({{x, y, z}, hashCell(x, y, z), static_cast<std::uint32_t>(i)});
        }
      }
    }
  }

  // Counting sort of the entries by bucket (stable, so each bucket lists boxes in index order).
  std::size_t buckets = 1;
  while (buckets < 2 * entries_.size()) buckets <<= 1;
  const std::uint32_t mask = static_cast<std::uint32_t>(buckets - 1);
  bucket_start_.assign(buckets + 1, 0);
  for (CellEntry& entry : entries_) {
    entry.bucket &= mask;
    ++bucket_start_[entry.bucket + 1];
  }
  for (std::size_t b = 0; b < buckets; ++b) bucket_start_[b + 1] += bucket_start_[b];
  sorted_entries_.resize(entries_.size());
  {
    std::vector<std::uint32_t>& cursor = bucket_cursor_;
    cursor.assign(bucket_start_.begin(), bucket_start_.end() - 1);
    for (const CellEntry& entry : entries_) sorted_entries_[cursor[entry.bucket]++] = entry;
  }

  for (std::size_t b = 0; b < buckets; ++b) {
    const std::uint32_t begin = bucket_start_[b];
    const std::uint32_t end = bucket_start_[b + 1];
    for (std::uint32_t s = begin; s < end; ++s) {
      const CellEntry& p = sorted_entries_[s];
      for (std::uint32_t t = s + 1; t < end; ++t) {
        const CellEntry& q = sorted_entries_[t];
        if (p.cell[0] != q.cell[0] || p.cell[1] != q.cell[1] || p.cell[2] != q.cell[2]) continue;
        if (!boxesOverlap(lo, hi, p.index, q.index)) continue;
        // Two boxes share every cell of their overlap; report the pair from one cell only: the
        // one holding the low corner of the overlap.
        bool owner = true;
        for (int k = 0; k < 3 && owner; ++k) {
          const Real corner = std::max(lo(k, p.index), lo(k, q.index));
          owner = static_cast<std::int64_t>(std::floor(corner * inverse_cell)) == p.cell[k];
        }
        if (owner) pairs.push_back(ordered(p.index, q.index));
      }
    }
  }

  // Oversize boxes against everything else (a pair of oversize boxes once).
  for (std::size_t s = 0; s < oversize_.size(); ++s) {
    const std::uint32_t big = oversize_[s];
    for (Eigen::Index j = 0; j < n; ++j) {
      const auto other = static_cast<std::uint32_t>(j);
      if (other == big || !finiteBox(lo, hi, j)) continue;
      const bool other_oversize = std::binary_search(oversize_.begin(), oversize_.end(), other);
      if (other_oversize && other < big) continue;
      if (boxesOverlap(lo, hi, big, other)) pairs.push_back(ordered(big, other));
    }
  }
}

bool BroadphaseFinder::denseGrid(const Vec3Array& lo, const Vec3Array& hi, const Real largest,
                                 std::vector<IndexPair>& pairs) {
  if (!(largest > 0.0)) return false;
  const Eigen::Index n = lo.cols();
  // Cells a little wider than the widest box: two boxes that overlap have low corners less than
  // one cell apart on every axis, so their cells are neighbours (the margin absorbs rounding).
  const Real cell = largest * (1.0 + 1e-9);
  const Real inverse_cell = 1.0 / cell;
  Vec3 origin = Vec3::Constant(std::numeric_limits<Real>::infinity());
  Vec3 far_corner = -origin;
  for (Eigen::Index i = 0; i < n; ++i) {
    if (!finiteBox(lo, hi, i)) continue;
    origin = origin.cwiseMin(lo.col(i));
    far_corner = far_corner.cwiseMax(lo.col(i));
  }
  // A table of at most kDenseCellsPerBox cells per box, else the hashed grid.
  Real cells = 1.0;
  std::array<std::int64_t, 3> dims{};
  for (int k = 0; k < 3; ++k) {
    const Real span = std::floor((far_corner[k] - origin[k]) * inverse_cell) + 1.0;
    cells *= span;
    if (!(cells <= kDenseCellsPerBox * static_cast<Real>(n) + 64.0)) return false;
    dims[k] = static_cast<std::int64_t>(span);
  }
  const auto cell_count = static_cast<std::size_t>(cells);
  const auto cellOf = [&](const Eigen::Index i, const int k) {
    const auto c = static_cast<std::int64_t>(std::floor((lo(k, i) - origin[k]) * inverse_cell));
    return std::min(c, dims[k] - 1);
  };

  // Counting sort of the boxes by cell (stable: index order within a cell).
  cell_start_.assign(cell_count + 1, 0);
  box_cell_.resize(static_cast<std::size_t>(n));
  for (Eigen::Index i = 0; i < n; ++i) {
    if (!finiteBox(lo, hi, i)) {
      box_cell_[i] = kNoCell;
      continue;
    }
    const std::int64_t c = cellOf(i, 0) + dims[0] * (cellOf(i, 1) + dims[1] * cellOf(i, 2));
    box_cell_[i] = static_cast<std::uint32_t>(c);
    ++cell_start_[c + 1];
  }
  for (std::size_t c = 0; c < cell_count; ++c) cell_start_[c + 1] += cell_start_[c];
  cell_boxes_.resize(cell_start_[cell_count]);
  bucket_cursor_.assign(cell_start_.begin(), cell_start_.end() - 1);
  for (Eigen::Index i = 0; i < n; ++i) {
    if (box_cell_[i] != kNoCell) cell_boxes_[bucket_cursor_[box_cell_[i]]++] = i;
  }

  // The boxes in cell order, so the tests below read memory in sequence.
  sorted_boxes_.resize(cell_boxes_.size());
  for (std::size_t s = 0; s < cell_boxes_.size(); ++s) {
    const std::uint32_t i = cell_boxes_[s];
    sorted_boxes_[s] = {lo(0, i), lo(1, i), lo(2, i), hi(0, i), hi(1, i), hi(2, i)};
  }
  const auto overlap = [this](const std::uint32_t s, const std::uint32_t t) {
    const Box& p = sorted_boxes_[s];
    const Box& q = sorted_boxes_[t];
    return p[0] <= q[3] && q[0] <= p[3] && p[1] <= q[4] && q[1] <= p[4] && p[2] <= q[5] &&
           q[2] <= p[5];
  };

  // Each cell against itself and the 13 neighbours that come after it in (z, y, x) order, so a
  // pair of neighbouring cells is visited once. Cells x - 1, x, x + 1 of a row are contiguous in
  // the sorted boxes: the 13 cells are 5 ranges (x + 1; row y + 1; rows y - 1, y, y + 1 of z + 1).
  std::uint32_t range_begin[5];
  std::uint32_t range_end[5];
  std::size_t used = 0;
  for (std::int64_t z = 0; z < dims[2]; ++z) {
    for (std::int64_t y = 0; y < dims[1]; ++y) {
      for (std::int64_t x = 0; x < dims[0]; ++x) {
        const std::int64_t c = x + dims[0] * (y + dims[1] * z);
        const std::uint32_t begin = cell_start_[c];
        const std::uint32_t end = cell_start_[c + 1];
        if (begin == end) continue;
        int ranges = 0;
        const auto row = [&](const std::int64_t ny, const std::int64_t nz, const std::int64_t x0) {
          if (ny < 0 || ny >= dims[1] || nz >= dims[2]) return;
          const std::int64_t first = x + dims[0] * (ny + dims[1] * nz);
          const std::int64_t from = first + (std::max<std::int64_t>(x0, 0) - x);
          const std::int64_t to = first + (std::min<std::int64_t>(x + 1, dims[0] - 1) - x) + 1;
          if (from >= to) return;
          range_begin[ranges] = cell_start_[from];
          range_end[ranges] = cell_start_[to];
          ++ranges;
        };
        row(y, z, x + 1);
        row(y + 1, z, x - 1);
        for (std::int64_t ny = y - 1; ny <= y + 1; ++ny) row(ny, z + 1, x - 1);
        std::size_t candidates = end - begin;
        for (int r = 0; r < ranges; ++r) candidates += range_end[r] - range_begin[r];
        if (pairs.size() < used + candidates * (end - begin)) {
          pairs.resize(std::max(2 * pairs.size(), used + candidates * (end - begin)));
        }
        // Every candidate is written and kept only when it overlaps (no branch to mispredict).
        for (std::uint32_t s = begin; s < end; ++s) {
          const std::uint32_t p = cell_boxes_[s];
          for (std::uint32_t t = s + 1; t < end; ++t) {
            pairs[used] = ordered(p, cell_boxes_[t]);
            used += overlap(s, t);
          }
          for (int r = 0; r < ranges; ++r) {
            for (std::uint32_t t = range_begin[r]; t < range_end[r]; ++t) {
              pairs[used] = ordered(p, cell_boxes_[t]);
              used += overlap(s, t);
            }
          }
        }
      }
    }
  }
  pairs.resize(used);
  return true;
}

void bruteForcePairs(const Vec3Array& lo, const Vec3Array& hi, std::vector<IndexPair>& pairs) {
  pairs.clear();
  const Eigen::Index n = lo.cols();
  for (Eigen::Index i = 0; i < n; ++i) {
    if (!finiteBox(lo, hi, i)) continue;
    for (Eigen::Index j = i + 1; j < n; ++j) {
      if (finiteBox(lo, hi, j) && boxesOverlap(lo, hi, i, j)) {
        pairs.push_back({static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(j)});
      }
    }
  }
}

}  // namespace engine
}  // namespace mass_aggregate_sim
