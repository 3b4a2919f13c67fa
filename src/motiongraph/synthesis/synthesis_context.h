// What every synthesis command needs of a graph, set up once: the assembler on the target
// skeleton, the learnt forward and travel axes, per-frame tags, the edge tracks, and the feet with the
// foot contacts of every database frame (for the foot clean-up, synthesis/foot_cleanup.h).
#pragma once

#include <list>
#include <map>
#include <memory>
#include <mutex>
#include <span>
#include <string>
#include <vector>

#include "motiongraph/synthesis/edge_tracks.h"
#include "motiongraph/synthesis/foot_cleanup.h"
#include "motiongraph/synthesis/rest_endings.h"
#include "motiongraph/synthesis/rest_starts.h"
#include "motiongraph/synthesis/walk.h"

namespace mg {

// Each tag's costs as path and steering searches price the way to it (tag_distance.h), computed
// once per tag and penalties for every search of a context (a studio's sessions and paths,
// Python's controllers and paths); and, with no tag, the way to frames that travel at a pace
// (travelling_frames.h: travel_mps), with those frames' marks. It keeps the kKept costs and
// marks last asked for (a script sweeping a penalty or a pace would grow it without end); a
// search holds what it was given for as long as it needs it, evicted or not.
class TagCostCache {
 public:
  static constexpr size_t kKept = 16;
  struct Key {
    TagMask tag = 0;
    double per_frame = 0.0, transition_penalty = 0.0, bridge_penalty = 0.0;
    double travel_mps = 0.0;  // > 0 with tag 0: the costs to frames travelling at this pace
    bool operator==(const Key&) const = default;
  };
  using Costs = std::shared_ptr<const std::vector<double>>;
  using Marks = std::shared_ptr<const std::vector<TagMask>>;
  // The costs of `key`, made by `make` the first time (under the lock: concurrent sessions asking
  // for the same tag compute it once).
  template <class Make>
  Costs get(const Key& key, Make&& make) {
    return find_or_make(entries_, key, std::forward<Make>(make));
  }
  // The marks of the frames travelling at `travel_mps`, made by `make` the first time.
  template <class Make>
  Marks travelling(double travel_mps, Make&& make) {
    return find_or_make(travelling_, travel_mps, std::forward<Make>(make));
  }
  size_t size() {
    std::lock_guard<std::mutex> lock(mutex_);
    return entries_.size();
  }

 private:
  // The entry of `key` in `list`, moved to its front (the most recently asked); made and put there
  // when there is none, the least recently asked dropped beyond kKept.
  template <class K, class T, class Make>
  std::shared_ptr<const T> find_or_make(std::list<std::pair<K, std::shared_ptr<const T>>>& list, const K& key,
                                        Make&& make) {
    std::lock_guard<std::mutex> lock(mutex_);
    for (auto it = list.begin(); it != list.end(); ++it) {
      if (it->first == key) {
        list.splice(list.begin(), list, it);
        return list.front().second;
      }
    }
    list.emplace_front(key, std::make_shared<const T>(make()));
    if (list.size() > kKept) list.pop_back();
    return list.front().second;
  }
  std::mutex mutex_;
  std::list<std::pair<Key, Costs>> entries_;
  std::list<std::pair<double, Marks>> travelling_;
};

struct SynthesisContext {
  const MotionDatabase* db = nullptr;
  const MotionGraph* graph = nullptr;
  MotionAssembler assembler;
  std::vector<TagMask> frame_tags;
  EdgeTracks tracks;
  // The target skeleton's feet and every database frame's contacts; when the feet cannot be
  // found, frame_contacts is empty and feet_error says why (no clean-up then).
  FootJoints feet;
  std::vector<ContactMask> frame_contacts;
  std::string feet_error;
  // Shared by copies of the context (they hold the same graph).
  std::shared_ptr<TagCostCache> tag_costs = std::make_shared<TagCostCache>();
  // Where the character can come to rest (rest_endings.h), found the first time they are asked for
  // (forward kinematics of every clip's end and every edge's frames: a large library's synthesis
  // that never rests need not pay for them); shared by copies of the context.
  struct RestCache {
    std::once_flag found;
    RestEndings endings;
  };
  std::shared_ptr<RestCache> rest_cache = std::make_shared<RestCache>();
  const RestEndings& rest() const;
  // These endings instead, for this context alone (a test's own, or none).
  void set_rest(RestEndings endings);
  // The ways to start off from each frame held at rest (rest_starts.h), found the first time each
  // is asked for (forward kinematics of the clips the graph goes on from); shared by copies.
  struct StartCache {
    std::mutex mutex;
    std::map<int, std::vector<RestStart>> starts;  // by frame held
  };
  std::shared_ptr<StartCache> start_cache = std::make_shared<StartCache>();
  // The reference stays valid as long as the cache.
  const std::vector<RestStart>& rest_starts(int held_frame) const;

  // The placement that puts node `node`'s frame with its root at `at` facing `direction`
  // (unit, on the floor).
  FloorTransform placement_facing(int node, const Vec2& at, const Vec2& direction) const;
  // The placement that puts node `node`'s frame with its root at `at`, the skeleton's travel
  // axis (facing.h: its mean direction of travel) turned along `direction`: where a path starts,
  // the root going its way.
  FloorTransform placement_heading(int node, const Vec2& at, const Vec2& direction) const;
  // The same for the first frame edge `edge` plays (a transition's first frame is already
  // blended, a few millimetres from its node's frame).
  FloorTransform placement_heading_edge(int edge, const Vec2& at, const Vec2& direction) const;
  // The contact masks of the frames `edges` play, in order (none without feet): what a
  // steering decision's frames carry.
  std::vector<ContactMask> edges_contacts(std::span<const int> edges) const;
  // The contact masks of database frames `frames`, in order (none without feet): what the frames
  // played at rest carry (Walk::rest_frames).
  std::vector<ContactMask> frames_contacts(std::span<const int> frames) const;
  // The contact masks of frames made of `sources`, in order: each its dominant source frame's (none
  // without feet).
  std::vector<ContactMask> sources_contacts(std::span<const FrameSource> sources) const;
  // The contact masks of the frames assemble_walk() plays for `walk` (walk_sources: its edges'
  // frames and the end node's frame), each its dominant source frame's.
  std::vector<ContactMask> walk_contacts(const Walk& walk) const;
  // The tags of database frame `frame` (0 past the tags' span: no tags).
  TagMask frame_tag(int frame) const {
    return frame >= 0 && static_cast<size_t>(frame) < frame_tags.size() ? frame_tags[static_cast<size_t>(frame)]
                                                                         : TagMask{0};
  }
  // The tags of the frames a walk plays, as walk_sources gives the frames: each edge's track's
  // (a blended frame carries those of the side that weighs more), then its rest frames' or, with a
  // start node, its end node frame's.
  std::vector<TagMask> walk_tags(const Walk& walk) const;
  // The database frames of the frames a walk plays: its edges' frames, then its rest frames, or
  // without them, when it has a start node (assemble_walk's walks; steering's record of edges has
  // none), its end node's frame.
  std::vector<FrameSource> walk_sources(const Walk& walk) const;
  // A clean-up for motion on the target skeleton; fails with feet_error without feet.
  Result<FootCleanup> foot_cleanup(const FootCleanupSettings& settings) const;
  // Cleans the motion assemble_walk() played for `walk` (or its first motion.frame_count frames,
  // a path's motion cut where the path ends) from its first frame.
  Status clean_up_walk(const Walk& walk, FootCleanup& cleanup, Motion& motion) const;
  // The tag bit of a name (in any case, where only one tag is so named: "Walk" is walk), or an
  // error listing the graph's tags, and the tag a word of the clips' vocabulary stands for
  // (cmu_tags.h: "sprint" is a word for 'run').
  Result<TagMask> tag_mask(const std::string& name) const;
  // The graph's own spelling of the tag `name` asks for (tag_mask's: "Walk" -> "walk").
  Result<std::string> tag_name(const std::string& name) const;
};

// The tags of the frame a transition edge lands on (its target node's): for a bridge, the motion
// type it leads into. 0 without tags.
inline TagMask bridge_landing_tags(const SynthesisContext& context, const GraphEdge& edge) {
  return context.frame_tag(context.graph->nodes[edge.to_node].frame);
}

// Whether a transition edge is a bridge that does not lead into the motion type `asked` (0: none
// asked, so every bridge): the bridges path and steering searches price (--bridge-penalty).
inline bool unasked_bridge(const SynthesisContext& context, const GraphEdge& edge, TagMask asked) {
  return edge.bridge && (bridge_landing_tags(context, edge) & asked) == 0;
}

// What path and steering searches charge for taking transition edge `edge` while `asked` is asked
// for: the transition penalty, and the bridge penalty more for an unasked bridge. Their costs to a
// tag price the way there alike (tag_distance.h): their bounds rest on the two agreeing.
inline double transition_price(const SynthesisContext& context, const GraphEdge& edge, TagMask asked,
                               double transition_penalty, double bridge_penalty) {
  return unasked_bridge(context, edge, asked) ? transition_penalty + bridge_penalty : transition_penalty;
}

// target_skeleton -1: the skeleton of the database's first clip.
Result<SynthesisContext> make_synthesis_context(const MotionDatabase& db, const MotionGraph& graph,
                                                int target_skeleton = -1);

}  // namespace mg
