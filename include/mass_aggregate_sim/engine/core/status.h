#pragma once

#include <string>
#include <utility>

namespace mass_aggregate_sim {
namespace engine {

// The outcome of a request to the engine: either ok, or refused with a message saying why.
// A refused request has changed nothing.
class Status {
 public:
  static Status ok() { return Status(true, {}); }
  static Status error(std::string message) { return Status(false, std::move(message)); }

  bool isOk() const { return ok_; }
  explicit operator bool() const { return ok_; }
  const std::string& message() const { return message_; }

 private:
  Status(bool ok, std::string message) : ok_(ok), message_(std::move(message)) {}
  bool ok_;
  std::string message_;
};

// A value, or the Status that says why there is none.
template <typename T>
class Result {
 public:
  Result(T value)
      : status_(Status::ok()), value_(std::move(value)) {}         // NOLINT: implicit on purpose
  Result(Status status) : status_(std::move(status)), value_() {}  // NOLINT: implicit on purpose

  bool isOk() const { return status_.isOk(); }
  explicit operator bool() const { return isOk(); }
  const Status& status() const { return status_; }
  const std::string& message() const { return status_.message(); }
  const T& value() const { return value_; }
  const T& operator*() const { return value_; }
  // Moves the value out (for values too large to copy, such as a World).
  T take() && { return std::move(value_); }

 private:
  Status status_;
  T value_;
};

}  // namespace engine
}  // namespace mass_aggregate_sim
