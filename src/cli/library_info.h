// motiongraph info FOLDER|MANIFEST...: a library summarised as `build` reads it (motion database,
// database/database_loader.h): its clips at the database's rate with their tags, frames and
// travel, the tags' totals, the skeletons, the feet found and how often each is planted, and
// what loading chose or doubts (units, up axes, travel from the feet, clips that look wrong).
#pragma once

#include <string>
#include <vector>

#include "motiongraph/database/database_loader.h"

namespace mg::cli {

struct LibraryInfoOptions {
  DatabaseSettings database;  // as build makes them
  bool json = false;
};

// Folders and .toml manifests are a library: when any input is one, the whole of what is given
// is read as `build` reads it (info, convert).
bool is_library(const std::vector<std::string>& inputs);

// Prints the summary (text, or JSON with --json) on stdout, the loading's lines on stderr as
// `build` logs them; the exit status, with one error line on failure.
int run_library_info(const std::vector<std::string>& inputs, const LibraryInfoOptions& options);

}  // namespace mg::cli
