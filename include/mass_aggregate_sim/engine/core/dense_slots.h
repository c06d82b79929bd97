#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "mass_aggregate_sim/engine/core/stable_id.h"

namespace mass_aggregate_sim {
namespace engine {

// The id bookkeeping of a store kept dense (structure of arrays with no holes): stable ids (slot +
// generation) against dense indices. Removal moves the last element into the hole, so dense
// indices change and ids stay. The store moves its own arrays the same way (remove() says from
// where to where).
template <typename Id>
class DenseSlots {
 public:
  std::size_t size() const { return slot_of_dense_.size(); }

  // A new id at dense index size().
  Id add() {
    std::uint32_t slot;
    if (!free_slots_.empty()) {
      slot = free_slots_.back();
      free_slots_.pop_back();
    } else {
      slot = static_cast<std::uint32_t>(dense_of_slot_.size());
      dense_of_slot_.push_back(0);
      generation_of_slot_.push_back(0);
      slot_live_.push_back(false);
    }
    dense_of_slot_[slot] = static_cast<std::uint32_t>(size());
    slot_live_[slot] = true;
    slot_of_dense_.push_back(slot);
    return Id{slot, generation_of_slot_[slot]};
  }

  // Where the removal of a live id moves the last element: `from` (the last dense index) into
  // `to` (the removed one's); from == to when the removed one was last.
  struct Move {
    std::size_t from;
    std::size_t to;
  };
  Move remove(const Id id) {
    const std::size_t to = dense_of_slot_[id.index];
    const std::size_t from = size() - 1;
    if (from != to) {
      const std::uint32_t moved_slot = slot_of_dense_[from];
      slot_of_dense_[to] = moved_slot;
      dense_of_slot_[moved_slot] = static_cast<std::uint32_t>(to);
    }
    slot_of_dense_.pop_back();
    slot_live_[id.index] = false;
    ++generation_of_slot_[id.index];
    free_slots_.push_back(id.index);
    return Move{from, to};
  }

  void clear() {
    for (const std::uint32_t slot : slot_of_dense_) {
      slot_live_[slot] = false;
      ++generation_of_slot_[slot];
      free_slots_.push_back(slot);
    }
    slot_of_dense_.clear();
  }

  std::optional<std::size_t> find(const Id id) const {
    if (id.index >= slot_live_.size() || !slot_live_[id.index] ||
        generation_of_slot_[id.index] != id.generation) {
      return std::nullopt;
    }
    return dense_of_slot_[id.index];
  }
  std::size_t denseIndexUnchecked(const Id id) const { return dense_of_slot_[id.index]; }
  Id idAt(const std::size_t dense) const {
    const std::uint32_t slot = slot_of_dense_[dense];
    return Id{slot, generation_of_slot_[slot]};
  }

  // Says why an id is not live: unknown slot, or the generation it had versus the slot's now.
  std::string describeInvalid(const Id id, const std::string& what) const {
    if (!id.valid() || id.index >= slot_live_.size()) {
      return "unknown " + what + " id " + id.str() + " (no such slot)";
    }
    if (!slot_live_[id.index])
      return "stale " + what + " id " + id.str() + " (" + what + " was removed)";
    if (generation_of_slot_[id.index] != id.generation) {
      return "stale " + what + " id " + id.str() + " (slot " + std::to_string(id.index) +
             " now holds generation " + std::to_string(generation_of_slot_[id.index]) + ")";
    }
    return what + " id " + id.str() + " is live";
  }

 private:
  std::vector<std::uint32_t> slot_of_dense_;
  std::vector<std::uint32_t> dense_of_slot_;
  std::vector<std::uint32_t> generation_of_slot_;
  std::vector<bool> slot_live_;
  std::vector<std::uint32_t> free_slots_;
};

}  // namespace engine
}  // namespace mass_aggregate_sim
