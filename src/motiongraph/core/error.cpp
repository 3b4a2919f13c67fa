#include "motiongraph/core/error.h"

#include <fmt/format.h>

namespace mg {

std::string Error::to_string() const {
  if (file.empty()) return message;
  if (line > 0) return fmt::format("{}:{}: {}", file, line, message);
  return fmt::format("{}: {}", file, message);
}

}  // namespace mg
