#include "motiongraph/core/file_extension.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

namespace mg {

std::string lower_extension(std::string_view path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

}  // namespace mg
