// A fresh folder under the system's temporary folder for a test's files, removed when it ends.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>

#include <unistd.h>

#include <fmt/format.h>

#include "motiongraph/io/file.h"
#include "test_data.h"

namespace mg::test {

class TempFolder {
 public:
  explicit TempFolder(const std::string& name)
      : path_(std::filesystem::temp_directory_path() / fmt::format("motiongraph-{}-{}", name, ::getpid())) {
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempFolder() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempFolder(const TempFolder&) = delete;
  TempFolder& operator=(const TempFolder&) = delete;

  const std::filesystem::path& path() const { return path_; }
  // Writes a file at a path below the folder (its folders made); returns its full path.
  std::string write(const std::string& relative, const std::string& text) const {
    const std::filesystem::path file = path_ / relative;
    std::filesystem::create_directories(file.parent_path());
    auto s = write_file_atomic(file.string(), text);
    if (!s) throw std::runtime_error(s.error().to_string());
    return file.string();
  }
  // A path to a bundled file, relative to this folder (manifests resolve against their folder).
  std::string relative_data(const std::string& relative) const {
    return std::filesystem::relative(data_path(relative), path_).generic_string();
  }

 private:
  std::filesystem::path path_;
};

}  // namespace mg::test
