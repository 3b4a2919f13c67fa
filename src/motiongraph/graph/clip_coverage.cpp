// What a graph keeps of each clip (clip_coverage.h).
#include "motiongraph/graph/clip_coverage.h"

#include <algorithm>
#include <utility>

namespace mg {

std::vector<ClipCoverage> clip_coverage(const MotionGraph& graph, const MotionDatabase& db,
                                        std::span<const Transition> candidates) {
  const int frames = db.frame_count();
  // Frames the clip edges play: f1 .. f2-1 of each (motion_graph.h).
  std::vector<char> kept(static_cast<size_t>(frames), 0);
  for (const GraphEdge& e : graph.edges) {
    if (e.transition) continue;
    const int first = graph.nodes[e.from_node].frame;
    std::fill_n(kept.begin() + first, std::min(e.frame_count, frames - first), char{1});
  }
  std::vector<ClipCoverage> out(db.clips.size());
  std::vector<int> clip_of(static_cast<size_t>(frames), 0);
  for (size_t c = 0; c < db.clips.size(); ++c) {
    const DatabaseClip& clip = db.clips[c];
    out[c].clip = static_cast<int>(c);
    out[c].frames = clip.frame_count;
    for (int f = clip.first_frame; f < clip.first_frame + clip.frame_count && f < frames; ++f) {
      out[c].kept_frames += kept[f];
      clip_of[f] = static_cast<int>(c);
    }
  }
  // Per lost clip, the candidates that enter it from kept frames and leave it for kept frames,
  // as (frame in the clip, D).
  std::vector<std::vector<std::pair<int, float>>> entries(db.clips.size()), exits(db.clips.size());
  for (const Transition& t : candidates) {
    if (t.from_frame < 0 || t.from_frame >= frames || t.to_frame < 0 || t.to_frame >= frames) continue;
    const int from = clip_of[t.from_frame], to = clip_of[t.to_frame];
    if (out[from].kept_frames == 0 && kept[t.to_frame]) exits[from].emplace_back(t.from_frame, t.distance);
    if (out[to].kept_frames == 0 && kept[t.from_frame]) entries[to].emplace_back(t.to_frame, t.distance);
  }
  for (size_t c = 0; c < db.clips.size(); ++c) {
    std::sort(entries[c].begin(), entries[c].end());
    std::sort(exits[c].begin(), exits[c].end());
    // Exits in frame order, against the lowest D of the entries at earlier frames.
    float best_entry = -1.0f;
    size_t e = 0;
    for (const auto& [frame, distance] : exits[c]) {
      for (; e < entries[c].size() && entries[c][e].first < frame; ++e) {
        if (best_entry < 0.0f || entries[c][e].second < best_entry) best_entry = entries[c][e].second;
      }
      if (best_entry < 0.0f) continue;
      const float join = std::max(best_entry, distance);
      if (out[c].best_join < 0.0f || join < out[c].best_join) out[c].best_join = join;
    }
  }
  return out;
}

}  // namespace mg
