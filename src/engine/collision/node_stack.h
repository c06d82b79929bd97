#pragma once

#include <array>
#include <vector>

namespace mass_aggregate_sim {
namespace engine {

// The stack of a depth-first tree traversal: on the call stack for trees up to kInline deep, so a
// query allocates nothing; deeper trees (never seen with a balanced tree) fall back to the heap.
// The caller sizes it: a traversal that pops a node and pushes its children never holds more than
// height + 1 entries.
template <typename T>
class NodeStack {
 public:
  explicit NodeStack(const int capacity) {
    if (capacity > kInline) {
      heap_.resize(static_cast<std::size_t>(capacity));
      data_ = heap_.data();
    }
  }
  NodeStack(const NodeStack&) = delete;
  NodeStack& operator=(const NodeStack&) = delete;

  void push(const T& value) { data_[size_++] = value; }
  T pop() { return data_[--size_]; }
  bool empty() const { return size_ == 0; }

 private:
  static constexpr int kInline = 64;
  std::array<T, kInline> inline_;
  std::vector<T> heap_;
  T* data_ = inline_.data();
  int size_ = 0;
};

}  // namespace engine
}  // namespace mass_aggregate_sim
