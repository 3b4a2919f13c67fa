// The one place that touches the disk. Reading whole files as text, and writing atomically:
// the content goes to a temporary file beside the target, which is renamed into place only
// once complete, so an interrupted or failed run never leaves a torn or half-written output.
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "motiongraph/core/error.h"

namespace mg {

// What an empty name given for a file is told (the error names no file then).
inline constexpr const char* kEmptyFileName = "a file's name is empty ('')";

// A file's whole text; a pipe's (a FIFO) to its end.
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

// Before any work is done: each output (empty names skipped) lies in a folder that exists and
// takes a new file (one is made there and removed), is no folder itself, and is none of the
// inputs nor another output, so that a run never fails after writing some of its outputs, nor
// writes over a file it reads. Paths are compared as the files they name (links and "./"
// resolved).
Status check_outputs(const std::vector<std::string>& outputs, const std::vector<std::string>& inputs);

// The same check for a file a command reads that is not one of its arguments (a clip a folder
// holds, one a manifest names, an AMC's skeleton): refused when it is one of the `outputs`, the
// error naming the output, the file and `how` it is read ("a clip of the folder data/").
Status check_not_an_output(const std::string& read, const std::vector<std::string>& outputs, const std::string& how);

// Creates the folder and its missing parents (nothing to do when it exists).
Status create_folders(const std::string& path);

}  // namespace mg
