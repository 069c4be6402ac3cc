// Expected<T>: a value or a message a user can act on. Used for every failure caused by input
// from outside the program (files, flags, devices). C++20 has no std::expected yet.
#pragma once

#include <string>
#include <utility>
#include <variant>

#include <tessera/base/check.h>

namespace tessera {

struct Error {
  std::string message;
};

template <typename T>
class [[nodiscard]] Expected {
 public:
  Expected(T value) : state_(std::move(value)) {}
  Expected(Error error) : state_(std::move(error)) {}

  bool ok() const { return state_.index() == 0; }
  explicit operator bool() const { return ok(); }

  T& value() & {
    TESSERA_CHECK(ok()) << "value() of a failed Expected: " << error().message;
    return std::get<0>(state_);
  }
  const T& value() const& {
    TESSERA_CHECK(ok()) << "value() of a failed Expected: " << error().message;
    return std::get<0>(state_);
  }
  T&& value() && {
    TESSERA_CHECK(ok()) << "value() of a failed Expected: " << error().message;
    return std::get<0>(std::move(state_));
  }
  T* operator->() { return &value(); }
  const T* operator->() const { return &value(); }
  T& operator*() { return value(); }
  const T& operator*() const { return value(); }

  const Error& error() const {
    TESSERA_CHECK(!ok()) << "error() of a successful Expected";
    return std::get<1>(state_);
  }

 private:
  std::variant<T, Error> state_;
};

// Expected<void>: success or an error.
template <>
class [[nodiscard]] Expected<void> {
 public:
  Expected() = default;
  Expected(Error error) : error_(std::move(error)), failed_(true) {}

  bool ok() const { return !failed_; }
  explicit operator bool() const { return ok(); }
  const Error& error() const {
    TESSERA_CHECK(failed_) << "error() of a successful Expected";
    return error_;
  }

 private:
  Error error_;
  bool failed_ = false;
};

inline Error makeError(std::string message) {
  return Error{std::move(message)};
}

}  // namespace tessera
