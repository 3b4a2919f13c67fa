// The one place that touches the disk. Reading whole files as text, and writing atomically:
// the content goes to a temporary file beside the target, which is renamed into place only
// once complete, so an interrupted or failed run never leaves a torn or half-written output.
#pragma once

#include <memory>
#include <string>
#include <string_view>

#include "motiongraph/core/error.h"

namespace mg {

Result<std::string> read_text_file(const std::string& path);

// A whole file's bytes for reading only, mapped into memory where the system can (its pages
// filled in one call, none copied or zeroed: a graph file of hundreds of MB opens several times
// faster than by read_text_file), else read. Move-only; bytes() lives as long as it does.
class FileBytes {
 public:
  static Result<FileBytes> open(const std::string& path);
  FileBytes(FileBytes&&) noexcept;
  FileBytes& operator=(FileBytes&&) noexcept;
  ~FileBytes();
  std::string_view bytes() const { return bytes_; }

 private:
  FileBytes() = default;
  std::string_view bytes_;
  void* map_ = nullptr;  // the mapping, when mapped
  size_t map_size_ = 0;
  std::string read_;     // the bytes, when read
};

Status write_file_atomic(const std::string& path, std::string_view content);

// Creates the folder and its missing parents (nothing to do when it exists).
Status create_folders(const std::string& path);

}  // namespace mg
