// Stopping long work when its caller asks (Python's Ctrl-C, a progress callback's exception):
// the work takes a std::stop_token and, between its steps (a clip read, a distance tile, a
// threshold's path check, a path search), ends with stopped_error() once a stop is requested.
// A default std::stop_token never asks: work given none runs to its end.
#pragma once

#include <stop_token>

#include "motiongraph/core/error.h"

namespace mg {

// The error of work that stopped when asked (ErrorKind::kStopped): nothing of it is kept.
inline Error stopped_error() { return Error{"", 0, "stopped before the end, as asked", ErrorKind::kStopped}; }

// stopped_error() when a stop is requested, else Ok.
inline Status check_stop(const std::stop_token& stop) {
  if (stop.stop_requested()) return stopped_error();
  return Ok{};
}

}  // namespace mg
