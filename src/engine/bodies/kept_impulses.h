#pragma once
// The impulses of rows that the body solver makes afresh each step, kept to warm start the next
// step's rows, by a key that names the row across steps (a particle link's id, a particle pair
// contact's key). Collected after the solve in any order, sorted once, then looked up. Part of the
// world's state (hashed with it).

#include <algorithm>
#include <cstdint>
#include <vector>

#include "mass_aggregate_sim/engine/core/types.h"

namespace mass_aggregate_sim {
namespace engine {

class KeptImpulses {
 public:
  struct Entry {
    std::uint64_t key = 0;
    Real lower = 0.0;
    Real upper = 0.0;
    Vec3 friction = Vec3::Zero();  // a particle pair's
  };

  void clear() { entries_.clear(); }
  void add(const std::uint64_t key, const Real lower, const Real upper = 0.0,
           const Vec3& friction = Vec3::Zero()) {
    entries_.push_back(Entry{key, lower, upper, friction});
  }
  // After the adds, so that find() can search (the keys are unique).
  void sortByKey() {
    std::sort(entries_.begin(), entries_.end(),
              [](const Entry& x, const Entry& y) { return x.key < y.key; });
  }
  // The entry named `key`, or null.
  const Entry* find(const std::uint64_t key) const {
    const auto it =
        std::lower_bound(entries_.begin(), entries_.end(), key,
                         [](const Entry& e, const std::uint64_t k) { return e.key < k; });
    return it != entries_.end() && it->key == key ? &*it : nullptr;
  }
  const std::vector<Entry>& entries() const { return entries_; }
  void swap(KeptImpulses& other) { entries_.swap(other.entries_); }

 private:
  std::vector<Entry> entries_;
};

}  // namespace engine
}  // namespace mass_aggregate_sim
