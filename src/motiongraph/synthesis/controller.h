// Interactive control (Kovar et al. 2002, section 6 "future work"; the seed's steering with
// motion tags): the walk is extended from live input, a desired facing direction on the floor
// and optionally a motion tag. Each decision runs a bounded branch and bound (horizon_search.h)
// over about horizon_s seconds minimising, per frame, (1 - cos) of the angle between the
// character's facing (holding the travel, HeadingEditSettings::hold_travel: its heading,
// the direction it walks, travel_heading.h) and the desired direction, plus tag_penalty for a frame without the
// tag, and for a walk that reaches the horizon tag_lookahead times what any walk from where it
// ends must still pay before the tag (tag_distance.h: asked to run far from any way into
// running, every walk within a second is as far, and the character would walk on); it then
// commits whole edges for at least commit_s seconds and returns their frames.
// The expansion budget (and an optional time budget) bounds every decision, and the first
// (greedy) walk is always there, so a decision always answers in bounded time. The frames
// committed are turned toward the direction asked for by the heading edit (heading_edit.h), and
// the next decision starts where it left the character.
//
// Asked to rest (ControlInput::rest), the character comes to rest at the end of a clip that ends
// standing still (rest_endings.h) by the cheapest way there (cost_to_rest: frames until it
// stands, the transition and bridge penalties on the way), turned by the heading edit on the
// way and in the stopping clip, about the ankle of the foot that plants first for good once it
// plants (a pivot; ControllerDecision::contacts free it for the clean-up) and no more once the
// other plants (a turn asked with rest: it stands facing the way asked as far as its last steps
// allow, in the clip's own stance), plays
// that clip a decision's worth of frames at a time, and then holds its last frame (resting(),
// standing()). Asked to move again, it goes on from that frame where the graph has a node there (a
// library with clips that start from standing); where it has none (the pruning left the clip's end
// out as a dead end: every library tried), it starts off (rest_starts.h) as soon as it stands still
// (the stopping clip's still tail, 1.7 s on CMU 29, is no wait): one decision plays the start, the
// frame it stands in blended into a lead-in and the lead-in on to its node, turned by the heading
// edit, and the next searches on from the node. Of the starts from the frame held, those into the
// motion type asked for where any are (with none asked, the type it came to rest from, or the one
// the graph holds most of: a walk that stopped walks on, not off into a jump that starts from
// standing), of those the ones within kStartSlack of the nearest, and of those the one that ranks
// best on the distance and where it heads against the heading asked ((rank / nearest - 1) +
// (1 - cos), RestStart::rank_m, start_way()), turned toward it by up to kStartMaxTurnDeg. With no
// start either, rest is for good (rest_is_for_good()).
// Asked to move on its way to rest, before it stands still, the rest is taken back (take_back()):
// where it has played nothing of the stopping clip yet, it goes on from the clip's node; where the
// clip reaches a node of the graph within kStartBlendS, it plays on to it and goes on from there;
// else it starts off from the frames it is playing (find_starts_from: the stopping clip's frames
// to come blended into a lead-in, ranked by how soon it gets going too, kGoingMps, and chosen as a
// start from rest is). The rest it was coming to is
// then none (rest_frames(), rest_endings()). Where no start is found, it comes to rest and starts
// off from there.
// Where the graph has no clip that ends at rest (RestEndings::empty), rest is not heard: the search
// goes on with the tag.
#pragma once

#include <future>
#include <span>
#include <vector>

#include "motiongraph/synthesis/heading_edit.h"
#include "motiongraph/synthesis/horizon_search.h"
#include "motiongraph/synthesis/synthesis_context.h"

namespace mg {

// A start's distance within this many times the nearest's is as good a start (rest_starts.h).
constexpr double kStartSlack = 1.5;
// A start turns toward the heading asked by up to this much, about where it stands (rest_starts.h:
// its lead-ins go the way the pose held faces), the blend turning it as it steps off; where it
// heads is its root's way over the lead-in and kStartHeadingS past its node.
constexpr double kStartMaxTurnDeg = 45.0;
constexpr double kStartHeadingS = 1.0;

// Bounds of ControllerSettings::travel_mps (a sprint) and travel_penalty: past them the pace
// asked swamps every other cost (at 1e16 m/s the character stood still).
constexpr double kMaxTravelMps = 20.0;
constexpr double kMaxTravelPenalty = 1000.0;

struct ControlInput {
  Vec2 direction = Vec2(0.0, -1.0);  // unit, on the floor (default north, -z)
  TagMask tag = 0;                   // 0: any motion
  bool rest = false;                 // come to rest (and stay there; see above)
};

struct ControllerSettings {
  double horizon_s = 1.0;
  double commit_s = 0.2;
  double tag_penalty = 2.0;          // per frame; a full turn away costs 2 per frame
  // Per transition taken (as many frames facing 90 degrees off): keeps captured motion between
  // blends while the direction holds (0: none).
  double transition_penalty = 1.0;
  // Per bridge (GraphEdge::bridge) taken, on top of the transition penalty, unless it leads into
  // the motion tag asked for (its target node's frame carries it): unasked, the character keeps
  // its motion type rather than blend visibly into another, and asked for one it goes there
  // directly, not by way of a third (0: bridges cost as any transition).
  double bridge_penalty = 30.0;
  // Asked for a tag, a walk that reaches the horizon also costs tag_lookahead times what any walk
  // from where it ends must still pay before the tag (tag_distance.h: tag_penalty per frame, the
  // transition and bridge penalties per edge): the search heads for a tag beyond its horizon
  // instead of finding every walk within it as far. Below 1 the facing counts for more on the
  // way (0: the horizon only; at most 1).
  double tag_lookahead = 0.5;
  long long max_expansions = 3000;
  int beam_width = 8;                // HorizonSettings::beam_width (0: none)
  // Per decision; 0 (the default): only the expansion budget, so that the same inputs give the
  // same motion on any machine and under any load (3000 expansions take about 0.1 ms here).
  // A wall-clock budget cuts the search short when the machine is busy, and a search cut short
  // follows its first (greedy) walk: use it only where a late answer is worse than a poor one.
  double time_budget_s = 0.0;
  // With no motion type asked, the pace asked of a walk along the heading: each frame costs
  // travel_penalty per metre its root is behind a point that leaves where the decision starts at
  // travel_mps along the heading (0: none; a walk facing the way asked while standing in place
  // costs nothing else, and on libraries without motion types the character stood about).
  double travel_mps = 0.5;            // at most kMaxTravelMps
  double travel_penalty = 2.0;        // at most kMaxTravelPenalty
  int start_node = -1;               // -1: controller_start_node()
  // The committed frames turned toward the direction asked for (max_turn_deg_per_m 0: as the
  // graph plays them).
  HeadingEditSettings heading_edit;

  Status validate() const;
};

struct ControllerDecision {
  std::vector<int> edges;            // committed
  // Database frames played after the edges, as captured (Walk::rest_frames): the clip on to its
  // end as the character comes to rest, then its last frame held.
  std::vector<int> rest_frames;
  // A start from rest (rest_starts.h): the frames it plays, before any edge (the frame held blended
  // into the lead-in, then the lead-in as captured).
  std::vector<FrameSource> start_frames;
  int frames = 0;                    // appended to the motion: the start's, the edges' and the rest frames
  // Per frame appended, the foot contacts the clean-up should hold: each frame's own
  // (SynthesisContext::edges_contacts, frames_contacts), but for the foot the stopping clip
  // pivots on while it turns (free there, then planted where it pivoted); empty when the graph's
  // feet are not known (SynthesisContext::frame_contacts).
  std::vector<ContactMask> contacts;
  double search_seconds = 0.0;       // wall time of the decision
  long long expansions = 0;
  bool budget_exhausted = false;
};

// The database frames a decision's frames are made of, in order: its start's, its edges', its
// rest frames'.
std::vector<FrameSource> decision_sources(const SynthesisContext& context, const ControllerDecision& decision);

// The blends a decision plays: its transition edges, and its start from rest (one blend).
inline int decision_transitions(const MotionGraph& graph, const ControllerDecision& decision) {
  return count_transitions(graph, decision.edges) + (decision.start_frames.empty() ? 0 : 1);
}

// A start from rest a controller took: from the frame (counted from its first) its first frame
// is, and which; `under_way`: from the stopping clip under way, the rest taken back before it
// stood still.
struct StartTaken {
  long long frame = 0;
  RestStart start;
  bool under_way = false;
};

// The motion type (graph_from_candidates.h: not a modifier such as turn) most nodes carry, the
// type the graph holds most of; 0 when no node carries a type.
TagMask most_played_type(const SynthesisContext& context);

// Where a controller starts without a start node: the first node carrying `tag`, or with no tag
// (0) the first carrying travelling_type(), else most_played_type() (a steering session that asks
// for no motion type walks, rather than start among jumps or dance it could leave only through a
// bridge); node 0 when no node carries it.
int controller_start_node(const SynthesisContext& context, TagMask tag);

class Controller {
 public:
  // The character starts at `at` facing `direction` (unit).
  static Result<Controller> create(const SynthesisContext& context, const ControllerSettings& settings,
                                   const ControlInput& first_input, const Vec2& at = Vec2::Zero());

  void set_input(const ControlInput& input) { input_ = input; }
  const ControlInput& input() const { return input_; }
  const SearchState& state() const { return state_; }
  const HeadingEditStats& heading_edit_stats() const { return edit_.stats(); }
  // Whether the character has taken its way to rest: the decisions hold its last frame until it
  // is asked to move and can (rest_is_for_good()).
  bool resting() const { return resting_; }
  // Resting where the graph has no way on from the frame it holds and no start from it
  // (rest_starts.h; the first call finds the starts from the frame held).
  bool rest_is_for_good() const;
  // The starts from rest it took, in order.
  const std::vector<StartTaken>& starts() const { return starts_; }
  // The frames (counted from its first) from which it went on each time it took a rest back on
  // its way there (take_back()), in order: by a start (under_way, in starts() too) or through the
  // graph.
  const std::vector<long long>& rests_taken_back() const { return taken_back_; }
  // Resting with the clip it rests at played to its end: holding its last frame.
  bool standing() const;
  // Resting and standing still: from the frame from which the clip it rests at stands still
  // (rest_frame()) on, holding its last frame too. Asked to move now, it starts off at once.
  bool still() const {
    return resting_ && ending_next_ > 0 && ending_frames_[ending_next_ - 1] >= rest_->rest_frame;
  }
  // The frame (counted from the controller's first) from which it stood still each time it came to
  // rest, in order; the last one's (-1 before any).
  const std::vector<long long>& rest_frames() const { return rest_frames_; }
  long long rest_frame() const { return rest_frames_.empty() ? -1 : rest_frames_.back(); }
  // The ending it came to rest on each time, in the same order.
  const std::vector<const RestEnding*>& rest_endings() const { return rest_endings_; }
  // The ending it last came to rest on (null before).
  const RestEnding* rest_ending() const { return rest_; }
  // Decides and appends the next frames to `out` (a motion on the context's target skeleton,
  // e.g. from MotionAssembler::empty_motion()).
  ControllerDecision step(Motion& out);

 private:
  Controller(const SynthesisContext& context, const ControllerSettings& settings)
      : context_(&context),
        settings_(settings),
        edit_(settings.heading_edit, context.db->fps, context.tracks.forward_axis) {}
  // Plays `committed` (the first edges of `planned`, the walk the decision chose) into `out`,
  // turned by the heading edit.
  void play(std::span<const int> committed, std::span<const int> planned, Motion& out, ControllerDecision& decision);
  // A decision on the way to rest, or at it.
  void step_to_rest(Motion& out, ControllerDecision& decision);
  // Off from rest by a start (rest_starts.h); false when there is none from the frame held.
  bool start_off(Motion& out, ControllerDecision& decision);
  // Asked to move on its way to rest (see the header): true when the decision played frames; false
  // when it did not, resting() telling whether the rest was taken back (the search goes on from
  // the node it stands at) or not (no way on found: it comes to rest).
  bool take_back(Motion& out, ControllerDecision& decision);
  // The rest it was coming to is none: it goes on.
  void forget_rest();
  // Where it stands on the floor: the root of the stopping clip's last frame played, as placed, or
  // where the way there left it before the clip's first.
  Vec2 last_played_root() const;
  // Of `starts`, the one the choice in the header takes (null: none).
  const RestStart* choose_start(const std::vector<RestStart>& starts) const;
  // Plays `start` from `departures` (the frames blended from, one per blend frame, placed as the
  // stopping clip is; `from`: where the root of the last frame played stands), its frames turned by
  // start_turn and the heading edit, and the state on from its node.
  void play_start(const RestStart& start, std::span<const int> departures, const Vec2& from, bool under_way,
                  Motion& out, ControllerDecision& decision);
  // Of the stopping clip, up to `frames` frames from ending_next_ up to index `until`, as the
  // placement stands (the contacts freed where it pivots); `frames` is what is left.
  void play_ending(Motion& out, ControllerDecision& decision, int& frames, size_t until);
  // Up to `frames` frames at rest: the stopping clip's still to play, turned by the heading edit
  // until both feet have made their last plant, then (`hold`) its last frame held.
  void play_rest(Motion& out, ControllerDecision& decision, int frames, bool hold);
  // Where `start` heads as captured, placed where it starts (unit; zero where it goes nowhere): its
  // root's way from the lead-in's first frame to kStartHeadingS past its node, as far as the clip goes.
  Vec2 start_way(const RestStart& start) const;
  // The turn about `pivot` on the floor (where its root stands) that turns `start` toward the
  // heading asked, by at most kStartMaxTurnDeg (none without the heading edit).
  FloorTransform start_turn(const RestStart& start, const Vec2& pivot) const;
  // The heading edit of the stopping clip's frames [from, ending_next_), appended to `out` from
  // frame `first`.
  void edit_ending(Motion& out, int first, size_t from);
  const SynthesisContext* context_;
  ControllerSettings settings_;
  HeadingEdit edit_;
  ControlInput input_;
  SearchState state_;
  std::vector<double> rest_cost_;  // cost_to_rest, found the first time rest is asked for
  bool resting_ = false;
  const RestEnding* rest_ = nullptr;
  FloorTransform rest_placement_;
  std::vector<long long> rest_frames_;
  std::vector<const RestEnding*> rest_endings_;
  std::vector<int> ending_frames_;  // the ending's database frames, played a decision's worth at a time
  size_t ending_next_ = 0;
  size_t ending_turned_ = 0;  // the ending's frames before this index are turned by the heading edit,
  size_t ending_pivot_ = 0;   // those from this one about the ankle of the foot planted there for good
  int pivot_ankle_ = -1;      // that ankle (-1: no pivot)
  ContactMask pivot_bits_ = 0;  // its foot's contact bits, cleared while it pivots
  bool pivot_pinned_ = false;
  Vec2 pivot_at_ = Vec2::Zero();  // where it stands, once pinned
  Motion held_pose_;  // the ending's last frame as played (the heading edit turned it): the frame held
  // The motion types of the ending's first frame (where it has none, most_played_type()): those a
  // start with no tag asked goes on in.
  TagMask moving_types_ = 0;
  std::vector<StartTaken> starts_;
  std::vector<long long> taken_back_;
  // Finding the starts from the ending's last frame, begun as it takes its way to rest (the
  // context's cache holds them; the last copy of the future waits for the thread).
  std::shared_future<void> starts_found_;
};

// Bearing in degrees (0 north = -z, 90 east = +x) as a unit floor direction, and back.
Vec2 bearing_direction(double bearing_deg);
double direction_bearing(const Vec2& direction);

}  // namespace mg
