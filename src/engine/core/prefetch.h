#pragma once
// Asking for memory before it is read, where the order of access is the engine's own and not one
// the hardware prefetcher follows.

#include <cstddef>

namespace mass_aggregate_sim {
namespace engine {

// Every 64-byte line that [p, p + bytes) overlaps (p need not begin on one).
inline void prefetchBytes(const void* const p, const std::size_t bytes) {
  const char* const begin = static_cast<const char*>(p);
  for (std::size_t line = 0; line < bytes + 63; line += 64) __builtin_prefetch(begin + line);
}

}  // namespace engine
}  // namespace mass_aggregate_sim
