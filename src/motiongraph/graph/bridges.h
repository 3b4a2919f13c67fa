// Bridges between motion types, and between them and the clips of none (the untagged class,
// bridged as one more tag: untagged_bridge_tag). Transitions below the threshold connect frames
// of one kind of motion with each other; between kinds (walking and running of one subject, say) every
// candidate may lie above it, and the pruned graph then keeps one kind only. A bridge is one of
// the best candidates (lowest D, a local minimum like any other) from frames that all carry tag
// s to frames that all carry tag t, added for each ordered pair of tags (s, t) that no selected
// transition joins and whose cores share no frame: the best onto each set of tags t's frames
// carry (a run, a run that turns) and into each of its clips first, so that the pair's bridges
// lead into as many kinds of captured motion as they can (by D alone, subject 16's three best
// from walk to run land in runs turning 90 degrees, which a straight path cannot use). Bridges
// are reported apart, with their D, so the user sees what quality the connection costs; pruning
// treats them like any transition. A
// bridge's D can reach 100x the threshold, so it blends longer than a transition
// (bridge_blend_frames), and a cap keeps out those no blend makes acceptable; the pairs left
// unjoined are reported with the best D that would join them.
#pragma once

#include <span>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "motiongraph/core/error.h"
#include "motiongraph/database/motion_database.h"
#include "motiongraph/graph/motion_graph.h"
#include "motiongraph/graph/transition.h"

namespace mg {

struct BridgeSettings {
  int per_tag_pair = 3;          // bridges per ordered pair of tags (0: none)
  TagMask tags = ~TagMask{0};    // the tags to bridge between
  int locality_radius = 5;       // bridges of one pair lie at least this far apart (frames)
  double max_distance = -1.0;    // absolute D above which no bridge is made; < 0: no cap
  double max_blend_factor = 3.0; // a bridge blends over at most this many windows (1: as a transition)

  Status validate() const;
};

// Its JSON form, the one the graph file and the build report write: {"bridges_per_tag_pair",
// "max_bridge_distance", "bridge_blend_factor"} (tags and locality are build's own, not
// recorded). Reading keeps what graph files written before bridges were capped or blended
// longer meant: no cap, blended as a transition (factor 1).
void to_json(nlohmann::json& json, const BridgeSettings& bridges);
void from_json(const nlohmann::json& json, BridgeSettings& bridges);

// Why an ordered pair of tags has neither a transition nor a bridge.
enum class UnjoinedReason {
  kNoCore,       // one of the two tags forms no cycle of its own (so it has no core frames)
  kNoCandidate,  // no local minimum leads from the one's core to the other's
  kAboveCap,     // every such candidate lies above max_distance
};

struct UnjoinedPair {
  int from_tag = 0;
  int to_tag = 0;
  UnjoinedReason reason = UnjoinedReason::kNoCandidate;
  float best_distance = -1.0f;  // the lowest D of a candidate that would bridge them; < 0: none
};

struct TagPair {
  int from_tag = 0;
  int to_tag = 0;
  bool operator==(const TagPair&) const = default;
};

struct BridgeSelection {
  std::vector<Transition> bridges;      // sorted by (from_frame, to_frame)
  std::vector<UnjoinedPair> unjoined;   // by (from_tag, to_tag)
  // Pairs short of bridges (or of the sets of tags or clips they land on) whose level leaves
  // candidates to look at (see select_bridges): the
  // selection is final only when this is empty.
  std::vector<TagPair> incomplete;
};

// Levels are kept per ordered pair of tags, at from_tag * kBridgeTags + to_tag.
inline constexpr int kBridgeTags = 64;

// The tag the untagged class (window_membership.h's untagged_class_frames: clips of no motion
// type in a library with types) bridges as: the one after the database's, so that clips no
// transition below the threshold joins to the typed ones are bridged to them as a type is (a
// library of walks and of exercises on the spot, the exercises of no type, joined only with
// every type at the 10 cm ceiling). -1 when the class holds no frame, or the database has every
// tag there is.
int untagged_bridge_tag(const MotionDatabase& db, std::span<const char> untagged_class);

// The frames a bridge of distance D asks to blend over: k sqrt(D / threshold) rounded (the
// distance an RMS point error of D spreads over as many frames as a threshold one over k), at
// least k and at most k * max_blend_factor.
int bridge_blend_frames(const Transition& bridge, int window, double threshold, double max_blend_factor);

// Where a bridge's blend of bridge_blend_frames() frames (L) leaves and lands. It keeps the
// pairing of frames D was measured on: frame from_frame + p of the clip it leaves with frame
// to_frame - k + 1 + p of the one it arrives in (reading L frames from from_frame and L up to
// to_frame, as a transition of window k does, would pair frames L - k apart: a third of a
// second for subject 16's walk into its run, the walk's stance against the run's swing). So a
// longer blend is centred on the measured window: it leaves up to (L - k) / 2 frames before
// from_frame and lands the rest after to_frame, as far as the two clips hold frames and, given
// `core` (per frame, 1 where a blend may leave or land: place_bridge_blends gives the frames of
// the clip pieces a pruned graph plays that carry one set of tags), as far as the frames up to
// the moved ends are all core frames; where fewer are left, L
// is shortened, never below k. The bridge's D and floor alignment stay the measured window's.
struct BridgeBlend {
  int from_frame = 0;  // where the blend leaves: its first frame in the clip it leaves
  int to_frame = 0;    // where it lands: its last frame in the clip it arrives in
  int frames = 0;      // L
};
BridgeBlend bridge_blend(const MotionDatabase& db, const Transition& bridge, int window, double threshold,
                         double max_blend_factor, std::span<const char> core = {});

// The frames of a tag's core: the clip frames of the largest strongly connected region that
// the tag's own transitions (both windows carrying the tag) make (prune_motion_graph on them).
// Empty when the tag has no cycle (pruning leaves nothing); fails on any other error of
// building or pruning that graph (transitions outside the database, tags that do not cover it).
Result<std::vector<char>> tag_core_frames(const MotionDatabase& db, std::span<const Transition> selected,
                                          std::span<const TagMask> frame_tags, int window, int tag);

// The bridges to add to `selected`; window k. A bridge from s to u leaves from a frame of s's
// core and lands on a frame of u's core (cores[t] from tag_core_frames; a tag without a core
// gets no bridges), and its D is at most max_distance. Each pair's per_tag_pair bridges are, in
// order of D, the best candidate landing on each set of tags (frame_tags of the frame it lands
// on) not landed on yet, then the best landing in each clip (frame_clips: per frame; empty: all
// one clip) not landed in yet, then, while the pair is short of bridges, the best of the others;
// none within locality_radius frames of one taken before it, at either end. A pair whose cores share a frame needs
// none: the graph passes from one to the other there. Every ordered pair of distinct tags of
// settings.tags with a core or candidates, joined by neither a selected transition, a shared
// core frame nor a bridge, is listed in `unjoined`.
//
// `candidates` and `above` (each sorted by (from_frame, to_frame), every D of `above` larger
// than every D of `candidates`) are the local minima known. Empty `levels`: they are all of
// them. Else, kBridgeTags^2 D levels: for bridging s to u they hold every minimum leaving a
// frame of s's core and arriving at a frame of u's core with D at most levels[s * kBridgeTags +
// u] (+infinity: all), and the ones above it are not looked at. A pair whose bridges could still change with
// candidates above its level (short of bridges, or of the sets of tags or clips they land on,
// of those its landing frames hold) is listed in `incomplete`: raise its level (on_demand_candidates.h)
// and select again. The selection with no pair incomplete is the one all the minima give.
BridgeSelection select_bridges(std::span<const Transition> candidates, std::span<const Transition> selected,
                               std::span<const TagMask> frame_tags, std::span<const int> frame_clips,
                               std::span<const std::vector<char>> cores,
                               int window, const BridgeSettings& settings, std::span<const Transition> above = {},
                               std::span<const double> levels = {});

}  // namespace mg
