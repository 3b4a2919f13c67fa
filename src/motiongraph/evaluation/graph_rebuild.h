// What it takes to select transitions again on the candidates a graph file stores: the frame
// features (needed for the floor alignment of each transition) recomputed from the file's
// database and distance settings, and the transition, bridge and tag settings the graph was
// built with (pipeline/saved_settings.h). Settings a file does not record take build's defaults.
#pragma once

#include "motiongraph/core/error.h"
#include "motiongraph/graph/graph_file.h"
#include "motiongraph/graph/graph_from_candidates.h"
#include "motiongraph/metric/frame_features.h"

namespace mg {

struct GraphRebuild {
  FrameFeatures features;
  DistanceSettings distance;             // as the file was built (to recompute the distances)
  GraphFromCandidatesSettings settings;  // as the file was built (its threshold included)
};

// Fails when the settings are not the JSON build writes, or when the features' window is not
// the candidates' (the settings do not describe this file).
Result<GraphRebuild> prepare_graph_rebuild(const GraphFile& file, const std::string& file_name);

}  // namespace mg
