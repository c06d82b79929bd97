#pragma once

#include <algorithm>
#include <cassert>
#include <cstdint>
#include <vector>

#include "engine/collision/node_stack.h"
#include "engine/collision/ray_segment.h"
#include "mass_aggregate_sim/engine/core/transform.h"

namespace mass_aggregate_sim {
namespace engine {

// A bounding volume hierarchy of fattened boxes (the bodies' broadphase). Each proxy is a leaf
// holding its box grown by a margin, so a proxy that moves a little is not reinserted. Leaves go
// where the surface-area heuristic says, and rotations keep the height O(log n).
//
// The nodes live in one array and refer to each other by index, so a copy is a full, independent
// tree. A proxy id is its leaf's index: stable until destroyProxy, then reused. No randomness and
// no addresses: the same sequence of calls builds the same tree and visits in the same order.
class DynamicTree {
 public:
  static constexpr std::int32_t kNull = -1;

  explicit DynamicTree(Real margin);

  // Stores tight stretched by displacement (where it is expected to go next) and grown by the
  // margin.
  std::int32_t createProxy(const Aabb& tight, std::uint64_t user_data,
                           const Vec3& displacement = Vec3::Zero());
  void destroyProxy(std::int32_t proxy);
  // False, and nothing changes, while the stored box still contains tight stretched by
  // displacement (a body that speeds up must reach as far as it will go). Otherwise stores that
  // box grown by the margin, moves the leaf to its new place and returns true.
  bool moveProxy(std::int32_t proxy, const Aabb& tight, const Vec3& displacement);

  const Aabb& fatAabb(const std::int32_t proxy) const {
    assert(isProxy(proxy));
    return nodes_[static_cast<std::size_t>(proxy)].box;
  }
  std::uint64_t userData(const std::int32_t proxy) const {
    assert(isProxy(proxy));
    return nodes_[static_cast<std::size_t>(proxy)].user_data;
  }
  bool isProxy(std::int32_t id) const;

  Real margin() const { return margin_; }
  // Edges from the root to the deepest leaf (0 for one proxy or none).
  int height() const;
  int proxyCount() const { return proxy_count_; }
  // One more than the largest id ever handed out: a bound for arrays indexed by proxy id.
  std::int32_t idBound() const { return static_cast<std::int32_t>(nodes_.size()); }
  // The internal nodes' surface areas over the root's: the heuristic's cost, for tree quality.
  Real areaRatio() const;
  // For tests: links, heights, counts and that every internal box contains its children's.
  bool validate() const;

  // Rebuilds the whole tree top down from the proxies' stored boxes (splits chosen by binned
  // surface area), for a set that will not move much. Proxy ids and boxes are unchanged.
  void rebuild();

  // Calls f(proxy) for every proxy whose stored box overlaps box; f returns false to stop. f must
  // not change the tree.
  template <typename F>
  void query(const Aabb& box, F&& f) const;

  // Calls f(proxy, max_t) for the proxies whose stored box the segment origin + t direction,
  // t in [0, max_t], crosses, nearer subtrees first. f returns the new max_t: 0 (or less) stops,
  // max_t goes on, a smaller value clips the segment (a larger one does not lengthen it). f must
  // not change the tree.
  template <typename F>
  void rayCast(const Vec3& origin, const Vec3& direction, Real max_t, F&& f) const;

 private:
  struct Node {
    Aabb box;
    std::uint64_t user_data = 0;
    std::int32_t parent = kNull;  // the next free node while on the free list
    std::int32_t child1 = kNull;
    std::int32_t child2 = kNull;
    std::int32_t height = -1;  // 0 for a leaf, -1 for a free node
    bool isLeaf() const { return child1 == kNull; }
  };
  struct Candidate {
    Real inherited_cost;
    std::int32_t node;
  };
  struct RayEntry {
    std::int32_t node;
    Real entry;
  };

  Node& node(const std::int32_t i) { return nodes_[static_cast<std::size_t>(i)]; }
  const Node& node(const std::int32_t i) const { return nodes_[static_cast<std::size_t>(i)]; }
  std::int32_t allocateNode();
  void freeNode(std::int32_t i);
  void insertLeaf(std::int32_t leaf);
  void removeLeaf(std::int32_t leaf);
  std::int32_t bestSibling(const Aabb& box);
  void replaceChild(std::int32_t parent, std::int32_t old_child, std::int32_t new_child);
  // Heights and boxes from start up to the root, rotating where the children's heights differ by
  // more than one.
  void refitUpward(std::int32_t start);
  void refit(std::int32_t i);
  std::int32_t balance(std::int32_t a);
  std::int32_t rotateUp(std::int32_t a, std::int32_t tall);
  std::int32_t buildRange(std::size_t begin, std::size_t end);

  Real margin_;
  std::vector<Node> nodes_;
  std::int32_t root_ = kNull;
  std::int32_t free_list_ = kNull;
  int proxy_count_ = 0;
  // Scratch of insertion and rebuild, kept to avoid reallocating.
  std::vector<Candidate> candidates_;
  std::vector<std::int32_t> leaves_;
};

template <typename F>
void DynamicTree::query(const Aabb& box, F&& f) const {
  if (root_ == kNull) return;
  NodeStack<std::int32_t> stack(node(root_).height + 1);
  stack.push(root_);
  while (!stack.empty()) {
    const std::int32_t i = stack.pop();
    const Node& n = node(i);
    if (!n.box.overlaps(box)) continue;
    if (n.isLeaf()) {
      if (!f(i)) return;
    } else {
      stack.push(n.child2);
      stack.push(n.child1);
    }
  }
}

template <typename F>
void DynamicTree::rayCast(const Vec3& origin, const Vec3& direction, Real max_t, F&& f) const {
  const RaySegment ray(origin, direction);
  Real entry = 0.0;
  if (root_ == kNull || !(max_t >= 0.0) || !ray.enters(node(root_).box, max_t, entry)) return;
  NodeStack<RayEntry> stack(node(root_).height + 1);
  stack.push({root_, entry});
  while (!stack.empty()) {
    const RayEntry top = stack.pop();
    // The segment was clipped since this entry was pushed: it still crosses the box exactly when
    // it enters before the new end.
    if (top.entry > max_t) continue;
    const Node& n = node(top.node);
    if (n.isLeaf()) {
      const Real value = f(top.node, max_t);
      if (!(value > 0.0)) return;
      max_t = std::min(max_t, value);
      continue;
    }
    Real entry1 = 0.0;
    Real entry2 = 0.0;
    const bool hit1 = ray.enters(node(n.child1).box, max_t, entry1);
    const bool hit2 = ray.enters(node(n.child2).box, max_t, entry2);
    if (hit1 && hit2) {
      // The nearer child on top: its hits clip the segment before the farther one is opened.
      if (entry2 < entry1) {
        stack.push({n.child1, entry1});
        stack.push({n.child2, entry2});
      } else {
        stack.push({n.child2, entry2});
        stack.push({n.child1, entry1});
      }
    } else if (hit1) {
      stack.push({n.child1, entry1});
    } else if (hit2) {
      stack.push({n.child2, entry2});
    }
  }
}

}  // namespace engine
}  // namespace mass_aggregate_sim
