#include "engine/collision/dynamic_tree.h"

#include <array>
#include <limits>

namespace mass_aggregate_sim {
namespace engine {
namespace {

constexpr Real kInfinity = std::numeric_limits<Real>::infinity();
// Candidate split planes per node of the rebuild: 15, evenly spaced across the box centres.
constexpr int kRebuildBins = 16;

const Aabb kEmptyBox{Vec3::Constant(kInfinity), Vec3::Constant(-kInfinity)};

}  // namespace

DynamicTree::DynamicTree(const Real margin) : margin_(margin) {}

namespace {

// The box swept by `tight` moved by `displacement`.
Aabb swept(const Aabb& tight, const Vec3& displacement) {
  Aabb box = tight;
  for (int k = 0; k < 3; ++k) {
    if (displacement[k] < 0.0) {
      box.lower[k] += displacement[k];
    } else {
      box.upper[k] += displacement[k];
    }
  }
  return box;
}

}  // namespace

std::int32_t DynamicTree::createProxy(const Aabb& tight, const std::uint64_t user_data,
                                      const Vec3& displacement) {
  assert(tight.lower.allFinite() && tight.upper.allFinite() && displacement.allFinite());
  const std::int32_t proxy = allocateNode();
  Node& n = node(proxy);
  n.box = swept(tight, displacement).grown(margin_);
  n.user_data = user_data;
  n.height = 0;
  insertLeaf(proxy);
  ++proxy_count_;
  return proxy;
}

void DynamicTree::destroyProxy(const std::int32_t proxy) {
  assert(isProxy(proxy));
  removeLeaf(proxy);
  freeNode(proxy);
  --proxy_count_;
}

bool DynamicTree::moveProxy(const std::int32_t proxy, const Aabb& tight, const Vec3& displacement) {
  assert(isProxy(proxy));
  assert(tight.lower.allFinite() && tight.upper.allFinite() && displacement.allFinite());
  const Aabb reach = swept(tight, displacement);
  if (node(proxy).box.contains(reach)) return false;
  removeLeaf(proxy);
  node(proxy).box = reach.grown(margin_);
  insertLeaf(proxy);
  return true;
}

bool DynamicTree::isProxy(const std::int32_t id) const {
  return id >= 0 && id < idBound() && node(id).height == 0;
}

int DynamicTree::height() const { return root_ == kNull ? 0 : node(root_).height; }

Real DynamicTree::areaRatio() const {
  if (root_ == kNull) return 0.0;
  const Real root_area = node(root_).box.perimeter();
  if (!(root_area > 0.0)) return 0.0;
  Real total = 0.0;
  for (const Node& n : nodes_) {
    if (n.height > 0) total += n.box.perimeter();
  }
  return total / root_area;
}

bool DynamicTree::validate() const {
  const std::size_t size = nodes_.size();
  std::size_t free_count = 0;
  for (std::int32_t i = free_list_; i != kNull; i = node(i).parent) {
    if (i < 0 || static_cast<std::size_t>(i) >= size || node(i).height != -1) return false;
    if (++free_count > size) return false;  // a cycle
  }
  std::size_t reached = 0;
  int leaves = 0;
  if (root_ != kNull) {
    if (node(root_).parent != kNull) return false;
    std::vector<std::int32_t> stack{root_};
    while (!stack.empty()) {
      const std::int32_t i = stack.back();
      stack.pop_back();
      if (i < 0 || static_cast<std::size_t>(i) >= size || ++reached > size) return false;
      const Node& n = node(i);
      if (n.isLeaf()) {
        if (n.child2 != kNull || n.height != 0) return false;
        ++leaves;
        continue;
      }
      for (const std::int32_t child : {n.child1, n.child2}) {
        if (child < 0 || static_cast<std::size_t>(child) >= size) return false;
        const Node& c = node(child);
        if (c.parent != i || c.height < 0 || !n.box.contains(c.box)) return false;
        stack.push_back(child);
      }
      if (n.height != 1 + std::max(node(n.child1).height, node(n.child2).height)) return false;
    }
  }
  return leaves == proxy_count_ && reached + free_count == size;
}

void DynamicTree::rebuild() {
  leaves_.clear();
  for (std::size_t i = 0; i < nodes_.size(); ++i) {
    const auto index = static_cast<std::int32_t>(i);
    if (nodes_[i].height == 0) {
      leaves_.push_back(index);
    } else if (nodes_[i].height > 0) {
      freeNode(index);
    }
  }
  root_ = leaves_.empty() ? kNull : buildRange(0, leaves_.size());
  if (root_ != kNull) node(root_).parent = kNull;
}

std::int32_t DynamicTree::allocateNode() {
  if (free_list_ == kNull) {
    nodes_.emplace_back();
    return static_cast<std::int32_t>(nodes_.size() - 1);
  }
  const std::int32_t i = free_list_;
  free_list_ = node(i).parent;
  node(i) = Node{};
  return i;
}

void DynamicTree::freeNode(const std::int32_t i) {
  Node& n = node(i);
  n = Node{};
  n.parent = free_list_;
  free_list_ = i;
}

void DynamicTree::insertLeaf(const std::int32_t leaf) {
  if (root_ == kNull) {
    root_ = leaf;
    node(leaf).parent = kNull;
    return;
  }
  const Aabb box = node(leaf).box;
  const std::int32_t sibling = bestSibling(box);
  const std::int32_t old_parent = node(sibling).parent;
  const std::int32_t parent = allocateNode();
  Node& p = node(parent);
  p.parent = old_parent;
  p.child1 = sibling;
  p.child2 = leaf;
  if (old_parent == kNull) {
    root_ = parent;
  } else {
    replaceChild(old_parent, sibling, parent);
  }
  node(sibling).parent = parent;
  node(leaf).parent = parent;
  refitUpward(parent);
}

void DynamicTree::removeLeaf(const std::int32_t leaf) {
  if (leaf == root_) {
    root_ = kNull;
    return;
  }
  const std::int32_t parent = node(leaf).parent;
  const std::int32_t grandparent = node(parent).parent;
  const std::int32_t sibling =
      node(parent).child1 == leaf ? node(parent).child2 : node(parent).child1;
  node(sibling).parent = grandparent;
  if (grandparent == kNull) {
    root_ = sibling;
  } else {
    replaceChild(grandparent, parent, sibling);
  }
  freeNode(parent);
  node(leaf).parent = kNull;
  if (grandparent != kNull) refitUpward(grandparent);
}

// Branch and bound over the tree for the sibling that adds the least area: the new parent's area
// plus the growth of every ancestor. A subtree is opened only while its lower bound (the leaf's own
// area plus the growth inherited so far) beats the best cost found; candidates are taken cheapest
// first, ties by index, so the search does not depend on the heap's implementation.
std::int32_t DynamicTree::bestSibling(const Aabb& box) {
  const Real leaf_area = box.perimeter();
  const auto later = [](const Candidate& x, const Candidate& y) {
    return x.inherited_cost != y.inherited_cost ? x.inherited_cost > y.inherited_cost
                                                : x.node > y.node;
  };
  std::int32_t best = root_;
  Real best_cost = kInfinity;
  candidates_.clear();
  candidates_.push_back({0.0, root_});
  while (!candidates_.empty()) {
    std::pop_heap(candidates_.begin(), candidates_.end(), later);
    const Candidate candidate = candidates_.back();
    candidates_.pop_back();
    if (leaf_area + candidate.inherited_cost >= best_cost) break;
    const Node& n = node(candidate.node);
    const Real merged_area = n.box.merged(box).perimeter();
    const Real cost = merged_area + candidate.inherited_cost;
    if (cost < best_cost) {
      best_cost = cost;
      best = candidate.node;
    }
    if (n.isLeaf()) continue;
    const Real inherited = candidate.inherited_cost + (merged_area - n.box.perimeter());
    if (leaf_area + inherited >= best_cost) continue;
    for (const std::int32_t child : {n.child1, n.child2}) {
      candidates_.push_back({inherited, child});
      std::push_heap(candidates_.begin(), candidates_.end(), later);
    }
  }
  return best;
}

void DynamicTree::replaceChild(const std::int32_t parent, const std::int32_t old_child,
                               const std::int32_t new_child) {
  Node& p = node(parent);
  if (p.child1 == old_child) {
    p.child1 = new_child;
  } else {
    p.child2 = new_child;
  }
}

void DynamicTree::refitUpward(const std::int32_t start) {
  for (std::int32_t i = start; i != kNull; i = node(i).parent) {
    i = balance(i);
    refit(i);
  }
}

void DynamicTree::refit(const std::int32_t i) {
  Node& n = node(i);
  const Node& c1 = node(n.child1);
  const Node& c2 = node(n.child2);
  n.height = 1 + std::max(c1.height, c2.height);
  n.box = c1.box.merged(c2.box);
}

std::int32_t DynamicTree::balance(const std::int32_t a) {
  const Node& n = node(a);
  if (n.isLeaf()) return a;
  const std::int32_t difference = node(n.child2).height - node(n.child1).height;
  if (difference > 1) return rotateUp(a, n.child2);
  if (difference < -1) return rotateUp(a, n.child1);
  return a;
}

// tall, a child of a at least two levels taller than its sibling, takes a's place. tall keeps its
// taller child and gives a the other one in its place, so a shrinks; between children of equal
// height, a takes the one whose box merges smaller with a's remaining child.
std::int32_t DynamicTree::rotateUp(const std::int32_t a, const std::int32_t tall) {
  Node& na = node(a);
  Node& nt = node(tall);
  const std::int32_t remaining = na.child1 == tall ? na.child2 : na.child1;
  const Aabb& remaining_box = node(remaining).box;
  const Node& f = node(nt.child1);
  const Node& g = node(nt.child2);
  const bool give_first =
      f.height < g.height || (f.height == g.height && remaining_box.merged(f.box).perimeter() <
                                                          remaining_box.merged(g.box).perimeter());
  const std::int32_t given = give_first ? nt.child1 : nt.child2;
  const std::int32_t kept = give_first ? nt.child2 : nt.child1;

  nt.parent = na.parent;
  if (na.parent == kNull) {
    root_ = tall;
  } else {
    replaceChild(na.parent, a, tall);
  }
  replaceChild(a, tall, given);
  node(given).parent = a;
  na.parent = tall;
  nt.child1 = a;
  nt.child2 = kept;
  refit(a);
  refit(tall);
  return tall;
}

// Splits leaves_[begin, end) by binned surface area along the axis where the box centres spread
// the most; returns the subtree's root.
std::int32_t DynamicTree::buildRange(const std::size_t begin, const std::size_t end) {
  if (end - begin == 1) return leaves_[begin];
  Vec3 lowest = Vec3::Constant(kInfinity);
  Vec3 highest = Vec3::Constant(-kInfinity);
  for (std::size_t s = begin; s < end; ++s) {
    const Vec3 c = node(leaves_[s]).box.center();
    lowest = lowest.cwiseMin(c);
    highest = highest.cwiseMax(c);
  }
  const Vec3 spread = highest - lowest;
  int axis = 0;
  for (int k = 1; k < 3; ++k) {
    if (spread[k] > spread[axis]) axis = k;
  }

  std::size_t middle = begin + (end - begin) / 2;
  if (spread[axis] > 0.0) {
    const Real scale = static_cast<Real>(kRebuildBins) / spread[axis];
    const auto binOf = [&](const std::int32_t leaf) {
      const auto b = static_cast<int>((node(leaf).box.center()[axis] - lowest[axis]) * scale);
      return std::min(std::max(b, 0), kRebuildBins - 1);
    };
    std::array<Aabb, kRebuildBins> bin_box;
    std::array<std::size_t, kRebuildBins> bin_count{};
    bin_box.fill(kEmptyBox);
    for (std::size_t s = begin; s < end; ++s) {
      const int b = binOf(leaves_[s]);
      bin_box[b] = bin_box[b].merged(node(leaves_[s]).box);
      ++bin_count[b];
    }
    // Cost of splitting after bin b: the right side's part from a sweep down, then the left's.
    std::array<Real, kRebuildBins> right_cost{};
    Aabb right = kEmptyBox;
    std::size_t right_count = 0;
    for (int b = kRebuildBins - 1; b > 0; --b) {
      right = right.merged(bin_box[b]);
      right_count += bin_count[b];
      right_cost[b - 1] =
          right_count == 0 ? 0.0 : right.perimeter() * static_cast<Real>(right_count);
    }
    Aabb left = kEmptyBox;
    std::size_t left_count = 0;
    int best_bin = 0;
    Real best_cost = kInfinity;
    for (int b = 0; b + 1 < kRebuildBins; ++b) {
      left = left.merged(bin_box[b]);
      left_count += bin_count[b];
      const Real cost = left.perimeter() * static_cast<Real>(left_count) + right_cost[b];
      if (cost < best_cost) {
        best_cost = cost;
        best_bin = b;
      }
    }
    // The lowest and highest centres fall in the first and last bins: both sides are non-empty.
    std::size_t i = begin;
    std::size_t j = end;
    while (i < j) {
      if (binOf(leaves_[i]) <= best_bin) {
        ++i;
      } else {
        std::swap(leaves_[i], leaves_[--j]);
      }
    }
    if (i > begin && i < end) middle = i;
  }

  const std::int32_t child1 = buildRange(begin, middle);
  const std::int32_t child2 = buildRange(middle, end);
  const std::int32_t parent = allocateNode();
  Node& p = node(parent);
  p.child1 = child1;
  p.child2 = child2;
  refit(parent);
  node(child1).parent = parent;
  node(child2).parent = parent;
  return parent;
}

}  // namespace engine
}  // namespace mass_aggregate_sim
