// A count with its noun, singular for one: "1 clip", "3 clips", "1 match", "2 matches".
#pragma once

#include <string>
#include <string_view>

#include <fmt/format.h>

namespace mg {

// `many` defaults to `one` with an "s".
inline std::string counted(long long n, std::string_view one, std::string_view many = {}) {
  if (n == 1) return fmt::format("1 {}", one);
  return many.empty() ? fmt::format("{} {}s", n, one) : fmt::format("{} {}", n, many);
}

}  // namespace mg
