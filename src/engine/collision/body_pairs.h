#pragma once

#include <cstdint>
#include <vector>

#include "engine/collision/dynamic_tree.h"

namespace mass_aggregate_sim {
namespace engine {

// Two proxies of a DynamicTree whose stored boxes overlap, a < b.
struct ProxyPair {
  std::int32_t a;
  std::int32_t b;
  friend bool operator==(const ProxyPair& x, const ProxyPair& y) {
    return x.a == y.a && x.b == y.b;
  }
  friend bool operator<(const ProxyPair& x, const ProxyPair& y) {
    return x.a != y.a ? x.a < y.a : x.b < y.b;
  }
};

// The candidate pairs of one step: each moved proxy against the tree. Keeps its buffers between
// calls.
class PairFinder {
 public:
  // Every pair of overlapping stored boxes with at least one proxy in moved that
  // accept(userData(a), userData(b)) keeps (a < b), each once, sorted. moved holds live proxies
  // (repeats allowed). accept must not change the tree.
  template <typename Accept>
  void findPairs(const DynamicTree& tree, const std::vector<std::int32_t>& moved, Accept&& accept,
                 std::vector<ProxyPair>& pairs);

 private:
  void markMoved(const DynamicTree& tree, const std::vector<std::int32_t>& moved);
  void finish(const std::vector<std::int32_t>& moved, std::vector<ProxyPair>& pairs);

  enum : std::uint8_t { kStill = 0, kMoved = 1, kQueried = 2 };
  std::vector<std::uint8_t> state_;  // by proxy id
};

// The pairs kept from step to step, sorted. Stored boxes change only when a proxy is created or
// moveProxy returns true: with those proxies passed to PairFinder each step and, with what it
// finds, to update(), pairs() is every accepted pair of overlapping stored boxes. A kept pair is
// not filtered again: when the filter's answer for it changes (a joint added), dropping it is the
// caller's part.
class PersistentPairs {
 public:
  // Adds found (sorted, unique: PairFinder's output) and drops the pairs of a proxy in changed
  // (those whose stored boxes changed; repeats allowed) whose boxes no longer overlap; those
  // dropped are appended to ended when given. The pairs of other proxies are kept untested.
  void update(const DynamicTree& tree, const std::vector<ProxyPair>& found,
              const std::vector<std::int32_t>& changed, std::vector<ProxyPair>* ended = nullptr);
  // Drops the pairs holding proxy. Call before destroyProxy: the tree reuses the id.
  void removeProxy(std::int32_t proxy, std::vector<ProxyPair>* ended = nullptr);
  const std::vector<ProxyPair>& pairs() const { return pairs_; }

 private:
  std::vector<ProxyPair> pairs_;
  std::vector<ProxyPair> merged_;
  std::vector<std::uint8_t> changed_;  // by proxy id, during update
};

template <typename Accept>
void PairFinder::findPairs(const DynamicTree& tree, const std::vector<std::int32_t>& moved,
                           Accept&& accept, std::vector<ProxyPair>& pairs) {
  pairs.clear();
  markMoved(tree, moved);
  for (const std::int32_t p : moved) {
    std::uint8_t& state = state_[static_cast<std::size_t>(p)];
    if (state == kQueried) continue;
    state = kQueried;
    const std::uint64_t user_p = tree.userData(p);
    tree.query(tree.fatAabb(p), [&](const std::int32_t q) {
      // Two moved proxies find each other: the pair is kept from the query of the lower id.
      if (q == p || (q < p && state_[static_cast<std::size_t>(q)] != kStill)) return true;
      const std::uint64_t user_q = tree.userData(q);
      const bool accepted = p < q ? accept(user_p, user_q) : accept(user_q, user_p);
      if (accepted) pairs.push_back(p < q ? ProxyPair{p, q} : ProxyPair{q, p});
      return true;
    });
  }
  finish(moved, pairs);
}

}  // namespace engine
}  // namespace mass_aggregate_sim
