// motiongraph: motion graphs from motion capture (Kovar, Gleicher & Pighin 2002).
// Entry point: parses the command line with CLI11 and runs one subcommand. Exceptions never
// escape: they become one line on stderr and a non-zero exit.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <new>

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include "cli/commands.h"

namespace mg::cli {

int fail(const Error& error) {
  std::fprintf(stderr, "%s\n", error.to_string().c_str());
  return 1;
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
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
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
