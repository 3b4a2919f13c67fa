// The one place that touches the disk. Reading whole files as text, and writing atomically:
// the content goes to a temporary file beside the target, which is renamed into place only
// once complete, so an interrupted or failed run never leaves a torn or half-written output.
#pragma once

#include <string>
#include <string_view>

#include "motiongraph/core/error.h"

namespace mg {

Result<std::string> read_text_file(const std::string& path);

Status write_file_atomic(const std::string& path, std::string_view content);

// Creates the folder and its missing parents (nothing to do when it exists).
Status create_folders(const std::string& path);

}  // namespace mg
