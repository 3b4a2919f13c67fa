// The subcommands of the motiongraph CLI. Each registers its options on the CLI11 app and
// returns the process exit code when run; errors are printed as one line "FILE:LINE: what".
#pragma once

#include <functional>

#include <CLI/CLI.hpp>

#include "motiongraph/core/error.h"

namespace mg::cli {

// A subcommand: its CLI11 app (set when it was chosen) and what runs it after parsing.
struct Command {
  CLI::App* app = nullptr;
  std::function<int()> run;
};

Command add_info_command(CLI::App& app);
Command add_convert_command(CLI::App& app);
Command add_build_command(CLI::App& app);
Command add_inspect_command(CLI::App& app);
Command add_bench_command(CLI::App& app);
Command add_walk_command(CLI::App& app);
Command add_path_command(CLI::App& app);
Command add_steer_command(CLI::App& app);
Command add_eval_command(CLI::App& app);
Command add_serve_command(CLI::App& app);

// Prints "motiongraph: <error>" to stderr and returns the exit code for failed input (1).
int fail(const Error& error);
// The same for options whose values do not go together or are out of their range, found once
// the settings they make are checked (validate()): the exit code of a command line that cannot
// be used (2), as CLI11's own checks give.
int fail_usage(const Error& error);

// For an unsigned option (a seed): CLI11 reads "-1" as 2^64 - 1; this refuses a minus sign.
const CLI::Validator& not_negative();

}  // namespace mg::cli
