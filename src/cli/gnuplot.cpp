#include "cli/gnuplot.h"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string_view>

#include <fmt/format.h>
#include <sys/wait.h>
#include <unistd.h>

namespace mg::cli {

namespace fs = std::filesystem;

Status gnuplot_available() {
  const char* path = std::getenv("PATH");
  std::string_view rest = path ? path : "";
  while (true) {
    const size_t colon = rest.find(':');
    const std::string folder(rest.substr(0, colon));
    const fs::path candidate = fs::path(folder.empty() ? "." : folder) / "gnuplot";
    if (::access(candidate.c_str(), X_OK) == 0) return Ok{};
    if (colon == std::string_view::npos) break;
    rest.remove_prefix(colon + 1);
  }
  return Error{"", 0,
               "gnuplot is not installed, so no PNG plots (install gnuplot-nox, e.g. with scripts/install-deps.sh, "
               "or pass --no-plots for the CSV files only)"};
}

std::string gnuplot_quote(const std::string& text) {
  std::string quoted = "'";
  for (const char c : text) {
    quoted += c;
    if (c == '\'') quoted += '\'';
  }
  return quoted + "'";
}

Status plot_png(const std::string& commands, const std::string& png_path, int width, int height) {
  if (auto s = gnuplot_available(); !s) return s;
  const std::string temporary = png_path + ".tmp";
  FILE* gnuplot = ::popen("gnuplot", "w");
  if (gnuplot == nullptr) return Error{png_path, 0, "cannot start gnuplot"};
  const std::string script = fmt::format("set terminal pngcairo size {},{} font ',11'\nset output {}\n{}\nunset output\n",
                                         width, height, gnuplot_quote(temporary), commands);
  const bool written = std::fwrite(script.data(), 1, script.size(), gnuplot) == script.size();
  const int status = ::pclose(gnuplot);
  std::error_code ec;
  if (!written || status == -1 || !WIFEXITED(status) || WEXITSTATUS(status) != 0 || !fs::exists(temporary, ec)) {
    fs::remove(temporary, ec);
    return Error{png_path, 0, "gnuplot failed to draw the plot (its message is above)"};
  }
  fs::rename(temporary, png_path, ec);
  if (ec) return Error{png_path, 0, fmt::format("cannot write the plot: {}", ec.message())};
  return Ok{};
}

}  // namespace mg::cli
