// Spacing transitions: best first, a few departures per stretch of frames, optionally captured
// motion between an arrival and the next departure.
#include "motiongraph/graph/transition_spacing.h"

#include <algorithm>
#include <numeric>

#include <nlohmann/json.hpp>

namespace mg {

Status TransitionSpacing::validate() const {
  if (min_piece_frames < 0) return Error{"", 0, "the minimum piece must be >= 0 frames (0: off)"};
  if (out_window_frames < -1 || out_window_frames == 0 || out_window_frames > 10'000) {
    return Error{"", 0,
                 "the stretch transitions leaving are counted over must be from 1 to 10000 frames (or -1 for the "
                 "window)"};
  }
  if (max_out < 0) return Error{"", 0, "the transitions leaving a stretch must be >= 0 (0: no limit)"};
  return Ok{};
}

std::vector<Transition> space_transitions(std::span<const Transition> transitions, std::span<const int> clip_of_frame,
                                          int window, const TransitionSpacing& spacing) {
  const int piece = spacing.min_piece_frames;
  const int frames = static_cast<int>(clip_of_frame.size());
  std::vector<int> leaving(clip_of_frame.size(), 0);  // kept departures per frame
  std::vector<int> landing(clip_of_frame.size(), 0);  // kept arrivals per frame
  auto same_clip = [&](int f, int g) { return g >= 0 && g < frames && clip_of_frame[f] == clip_of_frame[g]; };
  // Any kept arrival in (a - piece, a]? Any kept departure in [b, b + piece)?
  auto lands_before = [&](int a) {
    for (int g = a; g > a - piece; --g) {
      if (!same_clip(a, g)) break;
      if (landing[g] > 0) return true;
    }
    return false;
  };
  auto leaves_after = [&](int b) {
    for (int g = b; g < b + piece; ++g) {
      if (!same_clip(b, g)) break;
      if (leaving[g] > 0) return true;
    }
    return false;
  };
  // Would a departure at a make some `width` consecutive frames of a's clip hold max_out + 1?
  const int width = spacing.out_window_for(window);
  auto crowded = [&](int a) {
    if (spacing.max_out == 0) return false;
    for (int start = a - width + 1; start <= a; ++start) {
      int count = 0;
      for (int g = start; g < start + width; ++g) {
        if (same_clip(a, g)) count += leaving[g];
      }
      if (count >= spacing.max_out) return true;
    }
    return false;
  };

  std::vector<int> order(transitions.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](int x, int y) { return transitions[x].distance < transitions[y].distance; });
  std::vector<Transition> kept;
  for (int i : order) {
    const Transition& t = transitions[i];
    const int a = t.from_frame, b = t.to_frame;
    if (a < 0 || b < 0 || a >= frames || b >= frames) continue;
    if (piece > 0) {
      if (lands_before(a) || leaves_after(b)) continue;
      // The transition itself: landing at b with its own departure a in [b, b + piece).
      if (same_clip(a, b) && a >= b && a < b + piece) continue;
    }
    if (crowded(a)) continue;
    ++leaving[a];
    ++landing[b];
    kept.push_back(t);
  }
  std::sort(kept.begin(), kept.end(), [](const Transition& x, const Transition& y) {
    return x.from_frame != y.from_frame ? x.from_frame < y.from_frame : x.to_frame < y.to_frame;
  });
  return kept;
}

void to_json(nlohmann::json& json, const TransitionSpacing& spacing) {
  json = {{"out_window_frames", spacing.out_window_frames},
          {"min_piece_frames", spacing.min_piece_frames},
          {"max_out", spacing.max_out}};
}

void from_json(const nlohmann::json& json, TransitionSpacing& spacing) {
  const TransitionSpacing defaults;
  spacing.out_window_frames = json.value("out_window_frames", defaults.out_window_frames);
  spacing.min_piece_frames = json.value("min_piece_frames", defaults.min_piece_frames);
  spacing.max_out = json.value("max_out", defaults.max_out);
}

}  // namespace mg
