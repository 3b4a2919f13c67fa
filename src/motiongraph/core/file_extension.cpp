#include "motiongraph/core/file_extension.h"

#include <filesystem>

#include "motiongraph/core/text.h"

namespace mg {

std::string lower_extension(std::string_view path) {
  return ascii_lower(std::filesystem::path(path).extension().string());
}

}  // namespace mg
