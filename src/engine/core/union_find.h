#pragma once
// Disjoint sets over 0..n-1 (the bodies' sleeping islands, the piles of grains on bodies): find
// with path halving, join keeping the smaller root, so a set's root is its least member.

#include <algorithm>
#include <cstddef>
#include <numeric>
#include <vector>

namespace mass_aggregate_sim {
namespace engine {

class UnionFind {
 public:
  UnionFind() = default;
  explicit UnionFind(const std::size_t n) { reset(n); }
  // n singletons again, the storage kept.
  void reset(const std::size_t n) {
    parent_.resize(n);
    std::iota(parent_.begin(), parent_.end(), std::size_t{0});
  }
  std::size_t find(std::size_t i) {
    while (parent_[i] != i) {
      parent_[i] = parent_[parent_[i]];
      i = parent_[i];
    }
    return i;
  }
  void join(const std::size_t a, const std::size_t b) {
    const std::size_t ra = find(a);
    const std::size_t rb = find(b);
    if (ra != rb) parent_[std::max(ra, rb)] = std::min(ra, rb);
  }

 private:
  std::vector<std::size_t> parent_;
};

}  // namespace engine
}  // namespace mass_aggregate_sim
