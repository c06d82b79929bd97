#pragma once

#include <cstdint>
#include <string>

namespace mass_aggregate_sim {
namespace engine {

// A stable handle: the slot index plus the generation the slot had when the thing was created.
// Removing it bumps its slot's generation, so every id that still names it becomes stale. Tag
// makes the ids of different stores different types (a particle id is never a body id).
template <typename Tag>
struct StableId {
  std::uint32_t index = kInvalidIndex;
  std::uint32_t generation = 0;

  static constexpr std::uint32_t kInvalidIndex = 0xFFFFFFFFu;

  bool valid() const { return index != kInvalidIndex; }
  // Packs into one integer for messages: generation in the high half, index in the low half.
  std::uint64_t packed() const { return (std::uint64_t{generation} << 32) | index; }
  static StableId fromPacked(std::uint64_t packed) {
    return StableId{static_cast<std::uint32_t>(packed & 0xFFFFFFFFu),
                    static_cast<std::uint32_t>(packed >> 32)};
  }
  std::string str() const { return std::to_string(index) + ":" + std::to_string(generation); }

  friend bool operator==(const StableId& a, const StableId& b) {
    return a.index == b.index && a.generation == b.generation;
  }
  friend bool operator!=(const StableId& a, const StableId& b) { return !(a == b); }
  friend bool operator<(const StableId& a, const StableId& b) { return a.packed() < b.packed(); }
};

}  // namespace engine
}  // namespace mass_aggregate_sim
