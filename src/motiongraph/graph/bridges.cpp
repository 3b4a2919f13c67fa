#include "motiongraph/graph/bridges.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdlib>
#include <limits>

#include <nlohmann/json.hpp>

#include "motiongraph/core/json_text.h"
#include "motiongraph/graph/window_membership.h"

namespace mg {

int untagged_bridge_tag(const MotionDatabase& db, std::span<const char> untagged_class) {
  const auto tags = static_cast<int>(db.tag_names.size());
  if (tags >= kBridgeTags || std::find(untagged_class.begin(), untagged_class.end(), 1) == untagged_class.end()) {
    return -1;
  }
  return tags;
}

Status BridgeSettings::validate() const {
  if (per_tag_pair < 0 || per_tag_pair > 1000) return Error{"", 0, "bridges per tag pair must be 0 to 1000"};
  if (locality_radius < 0) return Error{"", 0, "bridge locality radius must be >= 0"};
  if (!(max_blend_factor >= 1.0 && max_blend_factor <= 20.0)) {
    return Error{"", 0, "a bridge's longest blend must be 1 to 20 windows"};
  }
  return Ok{};
}

namespace {

// The tags every frame of [first, first + count) carries.
TagMask window_tags(std::span<const TagMask> frame_tags, int first, int count) {
  TagMask tags = ~TagMask{0};
  for (int f = first; f < first + count; ++f) {
    tags &= f >= 0 && f < static_cast<int>(frame_tags.size()) ? frame_tags[f] : TagMask{0};
  }
  return tags;
}

}  // namespace

Result<std::vector<char>> tag_core_frames(const MotionDatabase& db, std::span<const Transition> selected,
                                          std::span<const TagMask> frame_tags, int window, int tag) {
  const TagMask bit = TagMask{1} << tag;
  std::vector<Transition> within;
  for (const Transition& t : selected) {
    if ((window_tags(frame_tags, t.from_frame, window) & bit) && (window_tags(frame_tags, t.to_frame - window + 1, window) & bit)) {
      within.push_back(t);
    }
  }
  std::vector<char> core;
  auto graph = build_motion_graph(db, within, window);
  if (!graph) return graph.error();
  std::vector<TagMask> only(frame_tags.size());
  for (size_t f = 0; f < frame_tags.size(); ++f) only[f] = frame_tags[f] & bit;
  PruneSettings prune;
  prune.connected_tags = bit;
  if (auto pruned = prune_motion_graph(*graph, only, prune); !pruned) {
    if (pruned.error().kind == ErrorKind::kEmptyGraph) return core;  // no cycle: no core
    return pruned.error();
  }
  core.assign(frame_tags.size(), 0);
  for (const GraphEdge& edge : graph->edges) {
    if (edge.transition) continue;
    const int first = graph->nodes[edge.from_node].frame;
    for (int f = first; f < first + edge.frame_count && f < static_cast<int>(core.size()); ++f) core[f] = 1;
  }
  return core;
}

int bridge_blend_frames(const Transition& bridge, int window, double threshold, double max_blend_factor) {
  const double ratio = threshold > 0.0 ? std::sqrt(std::max(0.0, static_cast<double>(bridge.distance)) / threshold) : 1.0;
  return static_cast<int>(std::lround(window * std::clamp(ratio, 1.0, max_blend_factor)));
}

BridgeBlend bridge_blend(const MotionDatabase& db, const Transition& bridge, int window, double threshold,
                         double max_blend_factor, std::span<const char> core) {
  const int wanted = bridge_blend_frames(bridge, window, threshold, max_blend_factor);
  const DatabaseClip& leave = db.clips[db.clip_of(bridge.from_frame)];
  const DatabaseClip& arrive = db.clips[db.clip_of(bridge.to_frame)];
  // The frames a blend may take before the measured window's first pair and after its last: held
  // by both clips, and (with a core) core frames up to the moved end.
  auto in_core = [&](int f) {
    return core.empty() || (f >= 0 && f < static_cast<int>(core.size()) && core[f] != 0);
  };
  const int before_held =
      std::min(bridge.from_frame - leave.first_frame, bridge.to_frame - window + 1 - arrive.first_frame);
  const int after_held = std::min(leave.first_frame + leave.frame_count - (bridge.from_frame + window),
                                  arrive.first_frame + arrive.frame_count - 1 - bridge.to_frame);
  int before = 0;
  while (before < before_held && in_core(bridge.from_frame - before - 1)) ++before;
  int after = 0;
  while (after < after_held && in_core(bridge.to_frame + after + 1)) ++after;
  const int extra = std::max(0, wanted - window);
  int lead = std::min(extra / 2, before);
  const int trail = std::min(extra - lead, after);
  lead = std::min(extra - trail, before);
  return {bridge.from_frame - lead, bridge.to_frame + trail, window + lead + trail};
}

BridgeSelection select_bridges(std::span<const Transition> candidates, std::span<const Transition> selected,
                               std::span<const TagMask> frame_tags, std::span<const int> frame_clips,
                               std::span<const std::vector<char>> cores,
                               int window, const BridgeSettings& settings, std::span<const Transition> above,
                               std::span<const double> levels) {
  BridgeSelection out;
  std::vector<Transition>& bridges = out.bridges;
  if (settings.per_tag_pair == 0 || frame_tags.empty()) return out;
  // Per frame, once: the tags of the window leaving it and of the window arriving at it, and the
  // cores it lies in (a call sees a million candidates on a large library, and the threshold
  // search calls it dozens of times).
  const int frames = static_cast<int>(frame_tags.size());
  const WindowMembership windows = window_membership(frame_tags, settings.tags, window);
  std::vector<TagMask> in_core(frames, 0);
  const int core_count = std::min(kBridgeTags, static_cast<int>(cores.size()));
  for (int s = 0; s < core_count; ++s) {
    if (cores[s].empty()) continue;
    for (int f = 0; f < frames && f < static_cast<int>(cores[s].size()); ++f) {
      if (cores[s][f]) in_core[f] |= TagMask{1} << s;
    }
  }
  auto leaving = [&](const Transition& t) { return windows.leave[t.from_frame]; };
  auto arriving = [&](const Transition& t) { return windows.arrive[t.to_frame]; };
  // The pairs (s, u) a candidate may bridge: leaving frames of s that lack u, in s's core, and
  // landing on frames of u that lack s, in u's core.
  auto sources = [&](const Transition& t) { return leaving(t) & ~arriving(t) & in_core[t.from_frame]; };
  auto sinks = [&](const Transition& t) { return arriving(t) & ~leaving(t) & in_core[t.to_frame]; };
  auto each_bit = [](TagMask mask, auto&& f) {
    for (; mask != 0; mask &= mask - 1) f(std::countr_zero(mask));
  };
  // Which ordered pairs of tags (s, u), s != u, the selected transitions already join, core to core.
  constexpr int kTags = kBridgeTags;
  std::vector<char> joined(kTags * kTags, 0);
  for (const Transition& t : selected) {
    const TagMask from = leaving(t) & in_core[t.from_frame], to = arriving(t) & ~leaving(t) & in_core[t.to_frame];
    each_bit(from, [&](int s) { each_bit(to, [&](int u) { joined[s * kTags + u] = 1; }); });
  }
  // And the pairs whose cores share a frame (clips tagged both, such as CMU's run-and-jump ones):
  // the graph goes from one core to the other through it, both ways, with no transition at all.
  for (int f = 0; f < frames; ++f) {
    const TagMask in = in_core[f] & settings.tags;
    if ((in & (in - 1)) == 0) continue;  // in one core or none
    each_bit(in, [&](int s) {
      each_bit(in, [&](int u) {
        if (u != s) joined[s * kTags + u] = 1;
      });
    });
  }
  constexpr double kAll = std::numeric_limits<double>::infinity();
  auto level = [&](int pair) { return levels.empty() ? kAll : levels[static_cast<size_t>(pair)]; };
  // Only candidates that may bridge a pair not yet joined, at or below the pair's level, are
  // sorted: a small share of all local minima (when the cores are small, at the low thresholds
  // the automatic choice tries first, a tiny one). Filtering before the (stable) sort leaves
  // their order as it was.
  std::vector<const Transition*> by_distance;
  for (std::span<const Transition> part : {candidates, above}) {
    for (const Transition& c : part) {
      const TagMask to = sinks(c);
      if (to == 0) continue;
      bool wanted = false;
      each_bit(sources(c), [&](int s) {
        each_bit(to, [&](int u) {
          wanted = wanted || (!joined[s * kTags + u] && c.distance <= level(s * kTags + u));
        });
      });
      if (wanted) by_distance.push_back(&c);
    }
  }
  std::stable_sort(by_distance.begin(), by_distance.end(),
                   [](const Transition* x, const Transition* y) { return x->distance < y->distance; });
  // Each pair's candidates at or below its level and the cap, by D.
  constexpr int kBridgePasses = 3;  // onto new sets of tags, into new clips, any
  std::vector<std::vector<const Transition*>> eligible(kTags * kTags);
  std::vector<float> best(kTags * kTags, -1.0f);  // the lowest D of any candidate, cap or not
  const bool capped = settings.max_distance >= 0.0;
  for (const Transition* c : by_distance) {
    const TagMask to = sinks(*c);
    each_bit(sources(*c), [&](int s) {
      each_bit(to, [&](int u) {
        const int pair = s * kTags + u;
        if (joined[pair] || c->distance > level(pair)) return;
        if (best[pair] < 0.0f) best[pair] = c->distance;  // candidates come by D
        if (capped && c->distance > settings.max_distance) return;
        eligible[pair].push_back(c);
      });
    });
  }
  // By D, each pair's bridges land on as many kinds of the arriving type and in as many of its
  // clips as they can: first the best candidate onto each set of tags not landed on yet (a run,
  // a run that turns: subject 16's three best from walk to run all land in runs turning 90
  // degrees, which a straight path cannot use), then into each clip not landed in yet, then the
  // best of the rest; none within locality_radius frames of one taken before it, at either end.
  // (frame_clips is empty or holds every frame's clip.)
  const bool clips_given = frame_clips.size() == frame_tags.size();
  auto clip_of = [&](int frame) { return clips_given ? frame_clips[static_cast<size_t>(frame)] : 0; };
  std::vector<std::vector<const Transition*>> chosen(kTags * kTags);
  std::vector<std::array<int, kBridgePasses>> taken(kTags * kTags);  // chosen[pair].size() after each pass
  for (int pair = 0; pair < kTags * kTags; ++pair) {
    auto& list = chosen[pair];
    for (int pass = 0; pass < kBridgePasses; ++pass) {
      for (const Transition* c : eligible[pair]) {
        if (static_cast<int>(list.size()) >= settings.per_tag_pair) break;
        const bool fresh = std::none_of(list.begin(), list.end(), [&](const Transition* other) {
          switch (pass) {
            case 0: return frame_tags[other->to_frame] == frame_tags[c->to_frame];
            case 1: return clip_of(other->to_frame) == clip_of(c->to_frame);
            default: return other == c;
          }
        });
        const bool near = std::any_of(list.begin(), list.end(), [&](const Transition* other) {
          return std::abs(other->from_frame - c->from_frame) <= settings.locality_radius ||
                 std::abs(other->to_frame - c->to_frame) <= settings.locality_radius;
        });
        if (fresh && !near) list.push_back(c);
      }
      taken[pair][pass] = static_cast<int>(list.size());
    }
  }
  for (const auto& list : chosen) {
    for (const Transition* c : list) {
      const bool duplicate = std::any_of(bridges.begin(), bridges.end(), [&](const Transition& b) {
        return b.from_frame == c->from_frame && b.to_frame == c->to_frame;
      });
      if (!duplicate) bridges.push_back(*c);
    }
  }
  std::sort(bridges.begin(), bridges.end(), [](const Transition& x, const Transition& y) {
    return x.from_frame != y.from_frame ? x.from_frame < y.from_frame : x.to_frame < y.to_frame;
  });
  const int tag_count = std::min(kTags, static_cast<int>(cores.size()));
  // How many sets of tags and clips each pair's bridges could land on: the frames of u's core
  // whose arriving window carries u and not s. A pair is short of bridges while a pass ends with
  // fewer than per_tag_pair of them and fewer sets of tags (clips) landed on than that, for a
  // candidate above its level might then be taken.
  std::vector<std::vector<TagMask>> landable_sets(kTags * kTags);
  std::vector<int> landable_clips(kTags * kTags, 0), last_clip(kTags * kTags, -1);
  for (int f = 0; f < frames; ++f) {
    const TagMask arrive = windows.arrive[f];
    each_bit(in_core[f] & arrive & settings.tags, [&](int u) {
      each_bit(settings.tags & ~arrive, [&](int s) {
        const int pair = s * kTags + u;
        if (clip_of(f) != last_clip[pair]) ++landable_clips[pair];
        last_clip[pair] = clip_of(f);
        auto& sets = landable_sets[pair];
        if (std::find(sets.begin(), sets.end(), frame_tags[f]) == sets.end()) sets.push_back(frame_tags[f]);
      });
    });
  }
  auto landed_on = [&](int pair, auto&& key) {
    std::vector<long long> keys;
    for (const Transition* c : chosen[pair]) keys.push_back(key(c->to_frame));
    std::sort(keys.begin(), keys.end());
    return static_cast<int>(std::unique(keys.begin(), keys.end()) - keys.begin());
  };
  // The pairs short of bridges with candidates above their level still to look at.
  for (int s = 0; s < tag_count; ++s) {
    for (int u = 0; u < tag_count; ++u) {
      const int pair = s * kTags + u;
      const int n = settings.per_tag_pair;
      const auto& after = taken[pair];
      const bool full =
          after[kBridgePasses - 1] >= n &&
          (after[0] >= n ||
           landed_on(pair, [&](int f) { return static_cast<long long>(frame_tags[f]); }) >=
               static_cast<int>(landable_sets[pair].size())) &&
          (after[1] >= n || landed_on(pair, clip_of) >= landable_clips[pair]);
      if (u == s || !(settings.tags >> s & 1) || !(settings.tags >> u & 1) || joined[pair] || cores[s].empty() ||
          cores[u].empty() || full || level(pair) == kAll) {
        continue;
      }
      if (!(capped && level(pair) >= settings.max_distance && best[pair] >= 0.0f)) out.incomplete.push_back({s, u});
    }
  }
  for (int s = 0; s < tag_count; ++s) {
    for (int u = 0; u < tag_count; ++u) {
      const int pair = s * kTags + u;
      if (u == s || !(settings.tags >> s & 1) || !(settings.tags >> u & 1) || joined[pair] || !chosen[pair].empty()) {
        continue;
      }
      UnjoinedPair p{s, u, UnjoinedReason::kNoCandidate, best[pair]};
      if (cores[s].empty() || cores[u].empty()) {
        p.reason = UnjoinedReason::kNoCore;
      } else if (best[pair] >= 0.0f) {
        p.reason = UnjoinedReason::kAboveCap;
      }
      out.unjoined.push_back(p);
    }
  }
  return out;
}

void to_json(nlohmann::json& json, const BridgeSettings& bridges) {
  json = {{"bridges_per_tag_pair", bridges.per_tag_pair},
          {"max_bridge_distance", cap_json(bridges.max_distance)},
          {"bridge_blend_factor", bridges.max_blend_factor}};
}

void from_json(const nlohmann::json& json, BridgeSettings& bridges) {
  bridges.per_tag_pair = json.value("bridges_per_tag_pair", BridgeSettings{}.per_tag_pair);
  bridges.max_distance = cap_from_json(json, "max_bridge_distance");
  bridges.max_blend_factor = json.value("bridge_blend_factor", 1.0);
}

}  // namespace mg
