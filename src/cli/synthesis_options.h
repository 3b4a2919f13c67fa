// Options and steps shared by the synthesis commands (walk, path, steer): the graph to read,
// the output, the target skeleton and the optional JSON report.
#pragma once

#include <string>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "cli/motion_output.h"
#include "motiongraph/synthesis/synthesis_context.h"
#include "motiongraph/synthesis/walk.h"

namespace mg::cli {

struct SynthesisOptions {
  std::string graph;
  std::string output;
  std::string report;
  int skeleton = -1;

  void add_to(CLI::App& app) {
    app.add_option("GRAPH", graph, "A .mgraph file written by 'motiongraph build'")->required();
    app.add_option("-o,--output", output, "Output motion: .bvh (metres) or .json (world positions)")->required();
    app.add_option("--report", report, "Also write a JSON report of the result");
    app.add_option("--skeleton", skeleton,
                   "Index of the database skeleton to play everything on (default: the first clip's)");
  }
};

// The graph file and its synthesis context, loaded together so the context's pointers stay
// valid (the struct is not copied after loading).
struct LoadedGraph {
  GraphFile file;
  SynthesisContext context;
};

// Loads GRAPH and builds the context; checks the output's extension first.
Result<std::unique_ptr<LoadedGraph>> load_for_synthesis(const SynthesisOptions& options);

// Writes the motion and, when asked, the report (both atomically). The report gets
// "foot_slide" (evaluation/source_foot_slide.h): the motion's mean_mps, p95_mps,
// max_joint_step_m and contact_steps, the same for the clips the walk read ("source", their
// names under "clips") and output / source ("ratio", null where the source's is 0); or
// {"error": "..."} when a skeleton's feet cannot be found by name.
Status write_synthesis_outputs(const SynthesisOptions& options, const LoadedGraph& loaded, const Motion& motion,
                               const Walk& walk, nlohmann::json report);

}  // namespace mg::cli
