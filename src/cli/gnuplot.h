// PNG plots drawn by gnuplot (Debian's gnuplot-nox, installed by scripts/install-deps.sh): a
// script is piped to a gnuplot process, which writes the picture with its pngcairo terminal.
// The picture is written to a temporary name and renamed, like every output. No plotter is
// compiled in: without gnuplot on PATH, plotting is one clear error.
#pragma once

#include <string>

#include "motiongraph/core/error.h"

namespace mg::cli {

// Ok when a gnuplot executable is on PATH; else an error saying how to get one.
Status gnuplot_available();

// A gnuplot string literal of `text` (single quotes, doubled inside).
std::string gnuplot_quote(const std::string& text);

// Runs `commands` (plot settings and plot commands; no terminal or output) with the output set
// to png_path, width x height pixels.
Status plot_png(const std::string& commands, const std::string& png_path, int width = 900, int height = 560);

}  // namespace mg::cli
