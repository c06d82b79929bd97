#pragma once

#include <memory>
#include <utility>

namespace mass_aggregate_sim {
namespace engine {

// A part of an object's state kept on the heap, so the owner's header needs only T's declaration:
// copied and moved with its owner like a plain member. T must be complete where the owner's
// special members are defined. A moved-from Owned holds a default T again on its next use, so a
// moved-from owner is an empty, usable object rather than one that dereferences null.
template <typename T>
class Owned {
 public:
  Owned() = default;
  Owned(const Owned& other) : value_(other.value_ ? std::make_unique<T>(*other.value_) : nullptr) {}
  Owned& operator=(const Owned& other) {
    if (this != &other) value_ = other.value_ ? std::make_unique<T>(*other.value_) : nullptr;
    return *this;
  }
  Owned(Owned&&) noexcept = default;
  Owned& operator=(Owned&&) noexcept = default;
  ~Owned() = default;

  T& operator*() { return held(); }
  const T& operator*() const { return held(); }
  T* operator->() { return &held(); }
  const T* operator->() const { return &held(); }

 private:
  T& held() const {
    if (!value_) value_ = std::make_unique<T>();
    return *value_;
  }
  mutable std::unique_ptr<T> value_;
};

// Data derived from an object's state to save work, never state itself: a copy starts empty and
// derives it again, so nothing stale can be carried over. Moves keep it.
template <typename T>
class Derived {
 public:
  Derived() = default;
  Derived(const Derived&) {}
  Derived& operator=(const Derived& other) {
    if (this != &other) value_.reset();
    return *this;
  }
  Derived(Derived&&) noexcept = default;
  Derived& operator=(Derived&&) noexcept = default;
  ~Derived() = default;

  // Made on first use.
  T& operator*() const {
    if (!value_) value_ = std::make_unique<T>();
    return *value_;
  }
  T* operator->() const { return &**this; }
  // Forgets it (derived again on next use).
  void reset() { value_.reset(); }

 private:
  mutable std::unique_ptr<T> value_;
};

}  // namespace engine
}  // namespace mass_aggregate_sim
