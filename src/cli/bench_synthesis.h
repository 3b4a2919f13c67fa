// motiongraph bench synthesis GRAPH.mgraph: path synthesis and the controller measured in one
// run (see bench_synthesis.cpp).
#pragma once

#include <string>

namespace mg::cli {

int run_synthesis_bench(const std::string& graph_path);

}  // namespace mg::cli
