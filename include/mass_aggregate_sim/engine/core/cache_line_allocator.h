#pragma once
// An allocator whose blocks start on a 64-byte cache line. The vectorised passes load four
// doubles (32 bytes) at a time from the particle arrays; with malloc's 16-byte alignment half of
// those loads may straddle two cache lines, depending on where the heap happens to put an array,
// so a step's cost would change with unrelated allocations.

#include <cstddef>
#include <new>

namespace mass_aggregate_sim {
namespace engine {

template <typename T>
struct CacheLineAllocator {
  using value_type = T;
  static constexpr std::align_val_t kAlignment{64};

  CacheLineAllocator() = default;
  template <typename U>
  CacheLineAllocator(const CacheLineAllocator<U>&) {}  // NOLINT: converting, as allocators are

  T* allocate(const std::size_t n) {
    return static_cast<T*>(::operator new(n * sizeof(T), kAlignment));
  }
  void deallocate(T* const p, std::size_t) { ::operator delete(p, kAlignment); }

  template <typename U>
  bool operator==(const CacheLineAllocator<U>&) const {
    return true;
  }
  template <typename U>
  bool operator!=(const CacheLineAllocator<U>&) const {
    return false;
  }
};

}  // namespace engine
}  // namespace mass_aggregate_sim
