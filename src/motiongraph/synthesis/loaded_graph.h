// A graph file together with the synthesis context set up on it (synthesis_context.h), owned
// as one: the context points into the file's database and graph, so the pair is made once,
// in place, and can be neither copied nor moved (hold it by unique_ptr). What the synthesis
// commands, the studio and the tests play motion from.
#pragma once

#include <memory>
#include <string>

#include "motiongraph/core/error.h"
#include "motiongraph/graph/graph_file.h"
#include "motiongraph/synthesis/synthesis_context.h"

namespace mg {

class LoadedGraph {
 public:
  // Takes the file and sets up synthesis on `target_skeleton` (-1: the first clip's). Fails
  // when there is no such skeleton or the context cannot be made (errors name `file_name`).
  static Result<std::unique_ptr<LoadedGraph>> create(GraphFile file, const std::string& file_name,
                                                     int target_skeleton = -1);
  // Reads and parses the .mgraph file at `path` (graph_file.h), then create().
  static Result<std::unique_ptr<LoadedGraph>> load(const std::string& path, int target_skeleton = -1,
                                                   const GraphReadOptions& options = {});

  LoadedGraph(const LoadedGraph&) = delete;
  LoadedGraph& operator=(const LoadedGraph&) = delete;

  const GraphFile& file() const { return file_; }
  const SynthesisContext& context() const { return context_; }

 private:
  explicit LoadedGraph(GraphFile file) : file_(std::move(file)) {}

  GraphFile file_;
  SynthesisContext context_;  // points into file_
};

}  // namespace mg
