// The motion graph of a motion library, end to end (Kovar et al. 2002, section 3; DESIGN.md
// 2-4): load and resample the clips (database/), point clouds and per-frame features
// (metric/), the tiled distance stage and its local minima (from `cache` when it holds this
// key), the threshold (chosen from the data, path-checked, or as given), transitions and
// bridges, and the graph pruned to the largest strongly connected component per motion type
// (graph/). Returns the graph file to write, the report and the exports asked for, as bytes:
// the caller writes them (io/file.h). Nothing is printed but through `log` (and the distance
// stage's progress bar, on a terminal, when asked).
//
// With a team of processes (parallel/process_team.h; nullptr: this process alone) every process
// calls build_graph() with the same inputs and settings: all load the clips and share the
// distance stage (parallel/shared_candidates.h), rank 0 alone makes the rest and gets the
// outputs; the others get `worker` set and nothing to write. An error on any process fails the
// build on all of them, rank 0 with the message (the others with ErrorKind::kOtherProcess).
//
// Fails on invalid settings, unreadable inputs, and any stage's error. When pruning leaves
// nothing the build still succeeds with graph_status an ErrorKind::kEmptyGraph error that says
// which threshold would make a graph, and the report and exports for the user to see why.
#pragma once

#include <functional>
#include <span>
#include <stop_token>
#include <string>

#include <nlohmann/json.hpp>

#include "motiongraph/core/error.h"
#include "motiongraph/graph/graph_file.h"
#include "motiongraph/parallel/process_team.h"
#include "motiongraph/pipeline/build_settings.h"
#include "motiongraph/pipeline/distance_cache.h"

namespace mg {

struct BuildLog {
  std::function<void(const std::string&)> info;          // a stage done, what it found (may be empty)
  std::function<void(const std::string&)> warning;       // something the user should know (may be empty)
  std::function<void(const DatabaseLoadNotes&)> loaded;  // what loading chose by itself (units)
  bool progress_bar = false;                             // the reading's and distance stage's bars (core/progress.h)
  // How far the reading and the distance stage have got, a line every kProgressLineSeconds
  // (core/progress.h progress_text), terminal or not (may be empty).
  std::function<void(const std::string&)> progress;
  // Asks the build to stop (core/stop.h): between the clips it reads, the distance tiles, the
  // thresholds it tries and the path check's searches, it then fails with stopped_error() (a
  // distance stage stopped part-way is not cached). A team's other processes are not asked.
  std::stop_token stop;
};

struct GraphBuild {
  GraphFile file;              // complete, report_json included, when graph_status is ok
  Status graph_status = Ok{};  // kEmptyGraph when pruning left nothing
  nlohmann::json report;       // build_report.h, with "timings"; with "error" when no graph
  std::string matrix_npy;      // the exports asked for (BuildSettings::exports), else empty
  std::string matrix_png;
  std::string clouds_npy;
  bool worker = false;  // not rank 0 of a team: the rest is empty, nothing to write
};

Result<GraphBuild> build_graph(std::span<const std::string> inputs, const BuildSettings& settings,
                               DistanceCache* cache = nullptr, const BuildLog& log = {},
                               ProcessTeam* team = nullptr);

}  // namespace mg
