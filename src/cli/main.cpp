// motiongraph: motion graphs from motion capture (Kovar, Gleicher & Pighin 2002).
// Entry point: parses the command line with CLI11 and runs one subcommand. Exceptions never
// escape: they become one line on stderr and a non-zero exit.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <new>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include "cli/commands.h"

namespace mg::cli {

int fail(const Error& error) {
  std::fprintf(stderr, "%s\n", error.to_string().c_str());
  return 1;
}

int fail_usage(const Error& error) {
  fail(error);
  return 2;
}

const CLI::Validator& not_negative() {
  static const CLI::Validator validator(
      [](std::string& text) -> std::string {
        return text.find_first_not_of(" \t") != std::string::npos && text[text.find_first_not_of(" \t")] == '-'
                   ? "must be 0 or more, not " + text
                   : "";
      },
      "");
  return validator;
}

namespace {

// Every number option of `app` and its subcommands refuses nan and inf (CLI11 reads them, and
// its range checks let NaN through: --fps nan resampled nothing, silently).
void refuse_non_finite_numbers(CLI::App& app) {
  static const CLI::Validator finite(
      [](std::string& text) -> std::string {
        char* end = nullptr;
        const double value = std::strtod(text.c_str(), &end);
        return end != text.c_str() && !std::isfinite(value) ? "must be a finite number, not " + text : "";
      },
      "");
  for (CLI::Option* option : app.get_options()) {
    if (option->get_type_name().rfind("FLOAT", 0) == 0) option->check(finite);  // "FLOAT", "FLOAT:FLOAT in [...]"
  }
  for (CLI::App* sub : app.get_subcommands({})) refuse_non_finite_numbers(*sub);
}

// The edits (insertions, deletions, substitutions) that turn `a` into `b`.
size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diagonal = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

// "unknown command 'biuld': did you mean 'build'? (commands: info, convert, ...)", for a first
// argument that is no option and no command; empty otherwise. (CLI11 took it for a stray
// argument and said "A subcommand is required".)
std::string unknown_command(CLI::App& app, int argc, char** argv) {
  if (argc < 2 || argv[1][0] == '-') return "";
  const std::string_view word = argv[1];
  std::string names, closest;
  size_t closest_edits = 3;  // at most two edits away to be suggested
  for (const CLI::App* sub : app.get_subcommands({})) {
    if (sub->get_name() == word) return "";
    names += (names.empty() ? "" : ", ") + sub->get_name();
    if (const size_t edits = edit_distance(word, sub->get_name()); edits < closest_edits) {
      closest_edits = edits;
      closest = sub->get_name();
    }
  }
  return fmt::format("unknown command '{}'{} (commands: {}; see --help)", word,
                     closest.empty() ? "" : fmt::format(": did you mean '{}'?", closest), names);
}

}  // namespace

}  // namespace mg::cli

int main(int argc, char** argv) {
  auto logger = spdlog::stderr_color_mt("motiongraph");
  logger->set_pattern("motiongraph: %^%l%$: %v");
  spdlog::set_default_logger(logger);

  CLI::App app{"motiongraph: build motion graphs from motion capture and synthesize new motion.\n"
               "Reads CMU ASF/AMC, BVH, glTF and FBX; lengths in metres."};
  app.require_subcommand(1);
  // Usage errors, like input errors, are one line.
  app.failure_message([](const CLI::App*, const CLI::Error& e) {
    return "motiongraph: " + std::string(e.what()) + " (see --help)\n";
  });
  app.set_version_flag("--version", "motiongraph 0.1.0");
  const std::vector<mg::cli::Command> commands = {
      mg::cli::add_info_command(app),
      mg::cli::add_convert_command(app),
      mg::cli::add_build_command(app),
      mg::cli::add_inspect_command(app),
      mg::cli::add_bench_command(app),
      mg::cli::add_walk_command(app),
      mg::cli::add_path_command(app),
      mg::cli::add_steer_command(app),
      mg::cli::add_eval_command(app),
      mg::cli::add_serve_command(app),
  };
  mg::cli::refuse_non_finite_numbers(app);
  // A command line that cannot be parsed exits 2 (as a shell's builtins do); --help and
  // --version exit 0; every other error 1.
  if (const std::string unknown = mg::cli::unknown_command(app, argc, argv); !unknown.empty()) {
    std::fprintf(stderr, "motiongraph: %s\n", unknown.c_str());
    return 2;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  }
  try {
    for (const auto& command : commands) {
      if (command.app->parsed()) return command.run();
    }
    return 2;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "motiongraph: out of memory\n");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "motiongraph: %s\n", e.what());
  }
  return 1;
}
