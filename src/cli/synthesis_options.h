// Options and steps shared by the synthesis commands (walk, path, steer): the graph to read,
// the output, the target skeleton and the optional JSON report.
#pragma once

#include <chrono>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "cli/motion_output_options.h"
#include "motiongraph/evaluation/synthesis_run.h"
#include "motiongraph/export/motion_file.h"
#include "motiongraph/synthesis/loaded_graph.h"
#include "motiongraph/synthesis/synthesis_context.h"
#include "motiongraph/synthesis/walk.h"

namespace mg::cli {

struct SynthesisOptions {
  std::string graph;
  std::string output;
  std::string report;
  int skeleton = -1;
  bool no_cleanup = false;
  MotionOutputOptions motion_output;

  void add_to(CLI::App& app) {
    app.add_option("GRAPH", graph, "A .mgraph file written by 'motiongraph build'")->required();
    app.add_option("-o,--output", output, "Output motion: .bvh (metres), .glb (binary glTF 2.0: skeleton, animation and a stick figure, for game engines, Blender, three.js), .gltf (the same as JSON, one file), .fbx (binary FBX 7.4: the same in centimetres, for Maya, MotionBuilder, Unity, Unreal, Blender) or .json (world positions)")->required();
    app.add_option("--report", report,
                   "Also write a JSON report of the result (its figures, foot slide against the clips, the warnings "
                   "printed)");
    app.add_option("--skeleton", skeleton,
                   "Index of the database skeleton to play everything on (default: the first clip's)")
        ->check(CLI::Range(0, 1000000));
    app.add_flag("--no-cleanup", no_cleanup,
                 "Write the motion as played, without the foot clean-up (planted feet held on their plants by "
                 "two-bone leg IK, the root lowered where a leg cannot reach)");
    motion_output.add_to(app);
  }
};

// Loads GRAPH and sets up synthesis on --skeleton (synthesis/loaded_graph.h); checks the
// outputs first: the motion's extension, and that the motion and the report can be written and
// are neither GRAPH nor one of the command's other `inputs` (io/file.h check_outputs).
// The command line's own choices for the output (its format, by its extension, and the output
// settings): a usage error (exit 2) when they do not go, checked before anything is read.
Status check_output_options(const SynthesisOptions& options);

Result<std::unique_ptr<LoadedGraph>> load_for_synthesis(const SynthesisOptions& options,
                                                        const std::vector<std::string>& inputs = {});

// The run settings the options give (evaluation/synthesis_run.h), the report's seconds counted
// from `begin`.
SynthesisRunSettings run_settings(const SynthesisOptions& options, std::chrono::steady_clock::time_point begin);

// Prints a result's warnings (SynthesizedMotion::warnings), one line each.
void print_warnings(const std::vector<std::string>& warnings);

// Writes the motion and, when asked, the report (both atomically). The report gets
// "foot_slide" (evaluation/foot_slide_report.h) when it has none. JSON motion gets the feet's
// contacts per frame:
// `contacts`, or when empty those of the frames the walk plays.
Status write_synthesis_outputs(const SynthesisOptions& options, const LoadedGraph& loaded, const Motion& motion,
                               const Walk& walk, nlohmann::json report, std::vector<ContactMask> contacts = {});

}  // namespace mg::cli
