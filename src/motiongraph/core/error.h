// Errors as values: what went wrong, in which file and on which line (1-based; 0 when the
// error is not tied to a line). Parsers, builders and I/O return Result<T>; the apps turn an
// Error into the one line "FILE:LINE: message" and a non-zero exit.
#pragma once

#include <cassert>
#include <string>
#include <utility>
#include <variant>

namespace mg {

// What kind of failure, for callers that branch on it (never on message text).
enum class ErrorKind {
  kGeneral,
  kEmptyGraph,  // pruning left nothing: the transitions form no cycle
  kOtherProcess,  // another process of a parallel job failed; rank 0 reports why
  kNoSuchAnimation,  // a glTF or FBX file has no animation of the name asked for
  kStopped,  // the caller asked the work to stop before its end (core/stop.h)
  kBusy,  // a service is at its limit of work in hand; asking again later may succeed
};

struct Error {
  std::string file;
  int line = 0;
  std::string message;
  ErrorKind kind = ErrorKind::kGeneral;

  // "file:line: message", "file: message" without a line, "message" without a file.
  std::string to_string() const;
};

// Either a value or an Error. Deliberately small: C++20 has no std::expected yet.
template <class T>
class [[nodiscard]] Result {
 public:
  Result(T value) : state_(std::move(value)) {}          // NOLINT(google-explicit-constructor)
  Result(Error error) : state_(std::move(error)) {}      // NOLINT(google-explicit-constructor)

  bool ok() const { return state_.index() == 0; }
  explicit operator bool() const { return ok(); }

  T& value() & { assert(ok()); return std::get<0>(state_); }
  const T& value() const& { assert(ok()); return std::get<0>(state_); }
  T&& value() && { assert(ok()); return std::get<0>(std::move(state_)); }
  const Error& error() const { assert(!ok()); return std::get<1>(state_); }

  T* operator->() { return &value(); }
  const T* operator->() const { return &value(); }
  T& operator*() & { return value(); }
  const T& operator*() const& { return value(); }

 private:
  std::variant<T, Error> state_;
};

// Result for operations that produce nothing but may fail.
struct Ok {};
using Status = Result<Ok>;

}  // namespace mg
