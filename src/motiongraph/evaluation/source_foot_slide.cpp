// A walk's source clips, measured beside its output.
#include "motiongraph/evaluation/source_foot_slide.h"

#include <algorithm>
#include <limits>

namespace mg {

FootSlideSettings database_foot_slide_settings(const MotionDatabase& db) {
  FootSlideSettings settings;
  settings.joint_names = db.foot_names;
  return settings;
}

std::vector<int> walk_source_clips(const MotionGraph& graph, int start_node, std::span<const int> edges) {
  std::vector<int> clips;
  if (start_node >= 0 && start_node < graph.node_count()) clips.push_back(graph.nodes[start_node].clip);
  for (int e : edges) {
    const GraphEdge& edge = graph.edges[e];
    clips.push_back(graph.nodes[edge.from_node].clip);
    clips.push_back(graph.nodes[edge.to_node].clip);
  }
  std::sort(clips.begin(), clips.end());
  clips.erase(std::unique(clips.begin(), clips.end()), clips.end());
  return clips;
}

Result<FootSlideComparison> compare_foot_slide(const Skeleton& output_skeleton, const Motion& output,
                                               const MotionDatabase& db, std::span<const int> source_clips,
                                               const FootSlideSettings& settings) {
  FootSlideComparison comparison;
  auto measured = measure_foot_slide(output_skeleton, output, settings);
  if (!measured) return measured.error();
  comparison.output = *measured;
  FootSlideSamples source;
  for (int c : source_clips) {
    const DatabaseClip& clip = db.clips[c];
    auto samples = foot_slide_samples(db.skeletons[clip.skeleton], clip.motion, settings);
    if (!samples) return samples.error();
    source.add(*samples);
  }
  comparison.source = source.summary();
  comparison.source_clips.assign(source_clips.begin(), source_clips.end());
  return comparison;
}

double times_the_source(double output, double source) {
  return source > 0.0 ? output / source : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace mg
