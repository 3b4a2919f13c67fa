#include "motiongraph/parallel/process_team.h"

#include <cstdlib>

#include <fmt/format.h>

namespace mg {

namespace {

const char* environment(const char* name) {
  const char* value = std::getenv(name);
  return value != nullptr && *value != '\0' ? value : nullptr;
}

}  // namespace

bool launched_by_mpi() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"}) {
    if (environment(name) != nullptr) return true;
  }
  return false;
}

int launcher_processes() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE"}) {
    if (const char* value = environment(name)) return std::atoi(value);
  }
  return 0;
}

Status ProcessTeam::agree(const Status& local) {
  // Each process sends "" when it is fine, else its error's text.
  const std::vector<std::string> all = gather(local ? std::string() : "E" + local.error().to_string());
  std::string first_error;
  for (size_t r = 0; r < all.size() && first_error.empty(); ++r) {
    if (all[r].empty()) continue;
    first_error = r == 0 ? all[r].substr(1) : fmt::format("process {}: {}", r, all[r].substr(1));
  }
  const bool failed = broadcast(!first_error.empty());
  if (!failed) return Ok{};
  if (rank() != 0) return Error{"", 0, "another process failed", ErrorKind::kOtherProcess};
  if (!local) return local;
  return Error{"", 0, first_error};
}

}  // namespace mg
