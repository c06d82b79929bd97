#include "engine/collision/body_pairs.h"

#include <algorithm>
#include <iterator>

namespace mass_aggregate_sim {
namespace engine {

void PairFinder::markMoved(const DynamicTree& tree, const std::vector<std::int32_t>& moved) {
  const auto bound = static_cast<std::size_t>(tree.idBound());
  if (state_.size() < bound) state_.resize(bound, kStill);
  for (const std::int32_t p : moved) {
    assert(tree.isProxy(p));
    state_[static_cast<std::size_t>(p)] = kMoved;
  }
}

void PairFinder::finish(const std::vector<std::int32_t>& moved, std::vector<ProxyPair>& pairs) {
  for (const std::int32_t p : moved) state_[static_cast<std::size_t>(p)] = kStill;
  // Unique by construction; sorted so the order does not depend on the tree's shape.
  std::sort(pairs.begin(), pairs.end());
}

void PersistentPairs::update(const DynamicTree& tree, const std::vector<ProxyPair>& found,
                             const std::vector<std::int32_t>& changed,
                             std::vector<ProxyPair>* ended) {
  const auto bound = static_cast<std::size_t>(tree.idBound());
  if (changed_.size() < bound) changed_.resize(bound, 0);
  for (const std::int32_t p : changed) changed_[static_cast<std::size_t>(p)] = 1;
  merged_.clear();
  std::set_union(pairs_.begin(), pairs_.end(), found.begin(), found.end(),
                 std::back_inserter(merged_));
  pairs_.clear();
  for (const ProxyPair& pair : merged_) {
    const bool tested =
        changed_[static_cast<std::size_t>(pair.a)] || changed_[static_cast<std::size_t>(pair.b)];
    if (!tested || tree.fatAabb(pair.a).overlaps(tree.fatAabb(pair.b))) {
      pairs_.push_back(pair);
    } else if (ended != nullptr) {
      ended->push_back(pair);
    }
  }
  for (const std::int32_t p : changed) changed_[static_cast<std::size_t>(p)] = 0;
}

void PersistentPairs::removeProxy(const std::int32_t proxy, std::vector<ProxyPair>* ended) {
  const auto holds = [proxy](const ProxyPair& pair) { return pair.a == proxy || pair.b == proxy; };
  if (ended != nullptr)
    std::copy_if(pairs_.begin(), pairs_.end(), std::back_inserter(*ended), holds);
  pairs_.erase(std::remove_if(pairs_.begin(), pairs_.end(), holds), pairs_.end());
}

}  // namespace engine
}  // namespace mass_aggregate_sim
