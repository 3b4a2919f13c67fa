// The foot slide of synthesized motion beside that of the captured clips it was cut from
// (DESIGN.md section 5b: every result is measured against its source, "x times the capture").
//
// The source clips of a walk are the clips its edges read: a clip edge reads its own clip, a
// transition both the clip it leaves and the clip it lands in (motion_graph.h). Each is
// measured whole, on its own skeleton at the database's frame rate, and their samples are
// pooled (evaluation/foot_slide.h): the measure of the capture the walk stands on, in the same
// units and at the same frame rate as the output's.
#pragma once

#include <span>
#include <vector>

#include "motiongraph/evaluation/foot_slide.h"
#include "motiongraph/graph/motion_graph.h"

namespace mg {

struct FootSlideComparison {
  FootSlide output;
  FootSlide source;
  std::vector<int> source_clips;  // indices into MotionDatabase::clips, ascending
};

// The measure's settings with the feet the database names (db.foot_names: `--feet`, a
// manifest's [feet]; empty: found by name), as the clean-up finds them.
FootSlideSettings database_foot_slide_settings(const MotionDatabase& db);

// The clips `edges` read (see above), each once, ascending; the start node's clip as well.
std::vector<int> walk_source_clips(const MotionGraph& graph, int start_node, std::span<const int> edges);

// The output (on its skeleton) and the source clips measured with the same settings. Fails when
// a skeleton's feet cannot be found or the settings are wrong.
Result<FootSlideComparison> compare_foot_slide(const Skeleton& output_skeleton, const Motion& output,
                                               const MotionDatabase& db, std::span<const int> source_clips,
                                               const FootSlideSettings& settings = {});

// output / source: how many times the capture's; NaN when the source's is 0.
double times_the_source(double output, double source);

}  // namespace mg
