#pragma once
// A constraint side: one body of any kind, by its kind and its dense index in that kind's store.

#include <cassert>
#include <cstdint>

namespace mass_aggregate_sim {
namespace engine {

enum class BodyKind : std::uint8_t {
  kParticle = 0,
};

// The kind sits in the top bits, so a particle's handle is its dense index itself: the rows of a
// particle scene index their arrays with it as they would with a plain index.
class BodyRef {
 public:
  static constexpr int kIndexBits = 28;
  static constexpr std::uint32_t kMaxIndex = (std::uint32_t{1} << kIndexBits) - 1;

  constexpr BodyRef() = default;
  static constexpr BodyRef particle(const std::uint32_t index) {
    return BodyRef(BodyKind::kParticle, index);
  }
  constexpr BodyRef(const BodyKind kind, const std::uint32_t index)
      : value_((static_cast<std::uint32_t>(kind) << kIndexBits) | index) {}

  constexpr BodyKind kind() const { return static_cast<BodyKind>(value_ >> kIndexBits); }
  constexpr std::uint32_t index() const { return value_ & kMaxIndex; }
  // index() of a particle's handle, which is its value: no mask on the passes' address chains.
  std::uint32_t particleIndex() const {
    assert(kind() == BodyKind::kParticle);
    return value_;
  }
  constexpr bool operator==(const BodyRef other) const { return value_ == other.value_; }
  constexpr bool operator!=(const BodyRef other) const { return value_ != other.value_; }

 private:
  std::uint32_t value_ = 0;
};

}  // namespace engine
}  // namespace mass_aggregate_sim
