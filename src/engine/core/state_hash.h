#pragma once

#include <cstdint>
#include <cstring>

#include "mass_aggregate_sim/engine/core/types.h"

namespace mass_aggregate_sim {
namespace engine {

// 64-bit FNV-1a over the exact bits of what is added: equal only for bit-identical inputs.
class StateHasher {
 public:
  void add(const std::uint64_t value) {
    for (int byte = 0; byte < 8; ++byte) {
      hash_ ^= (value >> (8 * byte)) & 0xFFu;
      hash_ *= kPrime;
    }
  }
  void add(const Real value) {
    std::uint64_t bits;
    std::memcpy(&bits, &value, sizeof bits);
    add(bits);
  }
  void add(const Vec3& v) {
    add(v.x());
    add(v.y());
    add(v.z());
  }
  std::uint64_t value() const { return hash_; }

 private:
  static constexpr std::uint64_t kPrime = 0x100000001b3ull;
  std::uint64_t hash_ = 0xcbf29ce484222325ull;
};

}  // namespace engine
}  // namespace mass_aggregate_sim
