#include "motiongraph/synthesis/rest_endings.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "synthesis/search_test_graphs.h"
#include "synthesis/subject16_graph.h"
#include "test_data.h"

namespace mg {
namespace {

// Clips as a database and their graph without transitions (nodes at each clip's first and last
// frame), with its endings.
struct Clips {
  explicit Clips(const std::vector<std::string>& files) : db(test::small_database(files)) {}
  RestEndings endings() {
    graph = build_motion_graph(db, std::vector<Transition>{}, 10);
    EXPECT_TRUE(graph.ok());
    auto assembler = MotionAssembler::create(db, *graph, 0);
    EXPECT_TRUE(assembler.ok());
    return find_rest_endings(db, *graph, *assembler, {});
  }
  // The root's floor distance between two global frames.
  double floor_distance(int a, int b) const {
    const DatabaseClip& clip = db.clips[static_cast<size_t>(db.clip_of(a))];
    const Vec3 d =
        clip.motion.translations(b - clip.first_frame)[0] - clip.motion.translations(a - clip.first_frame)[0];
    return std::hypot(d.x(), d.z());
  }
  MotionDatabase db;
  Result<MotionGraph> graph = Error{"", 0, "not built"};
};

TEST(RestEndings, AClipThatWalksToItsEndHasNoneAndOneThatStopsHasOneAtEachNode) {
  Clips clips({"cmu/16/16_15.amc", "cmu/16/16_33.amc"});  // walk; slow walk, stop
  const RestEndings endings = clips.endings();
  const MotionGraph& graph = *clips.graph;
  const DatabaseClip& stops = clips.db.clips[1];
  ASSERT_EQ(endings.endings.size(), 2u);  // 16_33's first and last frame
  for (int n = 0; n < graph.node_count(); ++n) {
    const RestEnding* ending = endings.at(n);
    ASSERT_EQ(ending != nullptr, graph.nodes[n].clip == 1) << "node " << n;
    if (ending == nullptr) continue;
    EXPECT_EQ(ending->node, n);
    EXPECT_EQ(ending->last_frame, stops.first_frame + stops.frame_count - 1);
    // It stands from rest_frame on (a few centimetres of sway), and travelled in the second before.
    EXPECT_LT(clips.floor_distance(ending->rest_frame, ending->last_frame), 0.1);
    EXPECT_GT(clips.floor_distance(ending->rest_frame - static_cast<int>(clips.db.fps), ending->rest_frame), 0.15);
    const std::vector<int> frames = ending->frames(graph);
    ASSERT_FALSE(frames.empty());
    EXPECT_EQ(frames.front(), graph.nodes[n].frame);
    EXPECT_EQ(frames.back(), ending->last_frame);
    EXPECT_EQ(static_cast<int>(frames.size()), ending->last_frame - graph.nodes[n].frame + 1);
  }
  // From the clip's last frame it is already at rest.
  EXPECT_EQ(endings.at(graph.node_at_frame(stops.first_frame + stops.frame_count - 1))->frames_to_rest(graph), 0);
}

// A walk whose whole pose is held from a frame on stands from about there (the joints' speeds are
// averaged over a few frames); one whose root alone is held (a walk on the spot) does not stand.
TEST(RestEndings, AWalkWhosePoseIsHeldFromAFrameOnRestsFromThere) {
  Clips clips({"cmu/16/16_15.amc"});
  const int held = 60;
  DatabaseClip& clip = clips.db.clips[0];
  ASSERT_GT(clip.frame_count, held + 30);
  EXPECT_TRUE(clips.endings().empty());  // as captured, it walks to its end
  const Vec3 at = clip.motion.translations(held)[0];
  for (int f = held; f < clip.frame_count; ++f) clip.motion.translations(f)[0] = at;
  EXPECT_TRUE(clips.endings().empty()) << "the root held, the legs still step";
  const std::vector<Quat> pose(clip.motion.rotations(held).begin(), clip.motion.rotations(held).end());
  for (int f = held; f < clip.frame_count; ++f) std::copy(pose.begin(), pose.end(), clip.motion.rotations(f).begin());
  const RestEndings endings = clips.endings();
  ASSERT_EQ(endings.endings.size(), 2u);  // its first and last frame's nodes
  for (const RestEnding& ending : endings.endings) {
    EXPECT_NEAR(ending.rest_frame, held, kStillWindowFrames / 2 + 1);
    EXPECT_EQ(still_from(clips.db.skeletons[0], clip.motion, clips.db.fps), ending.rest_frame);
  }
}

// The definition, solved by relaxing every edge until nothing changes (Bellman-Ford).
std::vector<double> by_relaxation(const MotionGraph& graph, const RestEndings& endings, double transition,
                                  double bridge) {
  const double far = std::numeric_limits<double>::infinity();
  std::vector<double> d(static_cast<size_t>(graph.node_count()), far);
  for (const RestEnding& e : endings.endings) {
    d[static_cast<size_t>(e.node)] =
        std::min(d[static_cast<size_t>(e.node)], double(e.frames_to_rest(graph) + e.penalty_frames));
  }
  for (bool changed = true; changed;) {
    changed = false;
    for (const GraphEdge& edge : graph.edges) {
      const double via = d[static_cast<size_t>(edge.to_node)] + edge.frame_count +
                         (edge.transition ? transition : 0.0) + (edge.bridge ? bridge : 0.0);
      if (via < d[static_cast<size_t>(edge.from_node)] - 1e-12) {
        d[static_cast<size_t>(edge.from_node)] = via;
        changed = true;
      }
    }
  }
  for (double& v : d) v = v == far ? -1.0 : v;
  return d;
}

TEST(RestEndings, CostToRestIsTheCheapestWayToAnEndingOnRandomGraphs) {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 40; ++trial) {
    MotionGraph graph = test::random_search_graph(rng, 30, 40, 12);
    for (GraphEdge& edge : graph.edges) edge.bridge = edge.transition && rng() % 3 == 0;
    RestEndings endings;
    endings.of_node.assign(static_cast<size_t>(graph.node_count()), -1);
    for (int n = 0; n < graph.node_count(); ++n) {
      if (trial % 10 == 0 || rng() % 6 != 0) continue;  // every tenth graph has none
      endings.of_node[static_cast<size_t>(n)] = static_cast<int>(endings.endings.size());
      const int frame = graph.nodes[static_cast<size_t>(n)].frame;
      const int penalty = rng() % 3 == 0 ? 60 : 0;  // a rest from a landing
      endings.endings.push_back({n, frame + static_cast<int>(rng() % 40), frame + 50, penalty});
    }
    const double transition = (trial % 4) * 0.7, bridge = (trial % 3) * 10.0;
    const std::vector<double> fast = cost_to_rest(graph, endings, transition, bridge);
    const std::vector<double> slow = by_relaxation(graph, endings, transition, bridge);
    ASSERT_EQ(fast.size(), slow.size());
    for (size_t n = 0; n < fast.size(); ++n) EXPECT_NEAR(fast[n], slow[n], 1e-9) << "trial " << trial << " node " << n;
    if (endings.empty()) {
      EXPECT_EQ(fast, std::vector<double>(fast.size(), -1.0));
    }
  }
}

TEST(RestEndings, Subject16ComesToRestOnlyAtTheEndsOfItsStoppingClips) {
  const auto& s = test::subject16();
  const SynthesisContext& context = s.context();
  ASSERT_FALSE(context.rest().empty());  // "slow walk, stop" and "run/jog, sudden stop" end standing
  for (const RestEnding& ending : context.rest().endings) {
    const DatabaseClip& clip = context.db->clips[static_cast<size_t>(context.db->clip_of(ending.last_frame))];
    EXPECT_EQ(ending.last_frame, clip.first_frame + clip.frame_count - 1);
    EXPECT_EQ(context.graph->nodes[static_cast<size_t>(ending.node)].clip, context.db->clip_of(ending.last_frame));
    // Over its last half second the root travels less than 0.25 m/s would.
    const Vec3 a = context.assembler.root_position(ending.last_frame - static_cast<int>(context.db->fps / 2), {});
    const Vec3 b = context.assembler.root_position(ending.last_frame, {});
    EXPECT_LT(std::hypot(b.x() - a.x(), b.z() - a.z()), 0.125) << clip.name;
  }
  // Rest is reached from every node of a walk or a run (a pruned graph is strongly connected), but
  // not by a leap: from within a jump, only once it lands.
  const std::vector<double> costs = cost_to_rest(*context.graph, context.rest(), 1.0, 30.0);
  int reached = 0;
  for (int n = 0; n < context.graph->node_count(); ++n) {
    const std::string& clip = context.db->clips[static_cast<size_t>(context.graph->nodes[n].clip)].name;
    if (clip != "16_01" && clip != "16_05") {
      EXPECT_GE(costs[static_cast<size_t>(n)], 0.0) << clip;
    }
    reached += costs[static_cast<size_t>(n)] >= 0.0 ? 1 : 0;
  }
  EXPECT_LT(reached, context.graph->node_count());  // some nodes of the jumps cannot rest but by leaping
  int leaps = 0;
  for (int e = 0; e < context.graph->edge_count(); ++e) leaps += context.rest().leap(e) ? 1 : 0;
  EXPECT_GT(leaps, 0);
}

// An ending of a clip that leaps (no foot down for longer than kMaxFlightS) within kMaxRestLeadS
// before it stands rests from a landing, and costs kLandingRestPenaltyS more; the stopping clips'
// endings cost their frames alone. Judged here from the contacts, frame by frame.
TEST(RestEndings, ARestFromALandingCostsMore) {
  const auto& s = test::subject16();
  const SynthesisContext& context = s.context();
  const double fps = context.db->fps;
  int landings = 0, stops = 0;
  for (const RestEnding& ending : context.rest().endings) {
    const DatabaseClip& clip = context.db->clips[static_cast<size_t>(context.db->clip_of(ending.last_frame))];
    bool leapt = false;
    int off = 0;  // frames in a row with no foot down
    for (int f = std::max(clip.first_frame, ending.rest_frame - static_cast<int>(std::lround(kMaxRestLeadS * fps)));
         f < ending.rest_frame; ++f) {
      off = context.frame_contacts[static_cast<size_t>(f)] == 0 ? off + 1 : 0;
      leapt = leapt || off > std::lround(kMaxFlightS * fps);
    }
    EXPECT_EQ(ending.penalty_frames, leapt ? std::lround(kLandingRestPenaltyS * fps) : 0) << clip.name;
    EXPECT_EQ(ending.cost(*context.graph), ending.frames_to_rest(*context.graph) + ending.penalty_frames);
    (leapt ? landings : stops) += 1;
    if (clip.name == "16_33") {
      EXPECT_FALSE(leapt);  // slow walk, stop
    }
  }
  EXPECT_GT(landings, 0);  // 16_01 and 16_05, jumps that land and stand
  EXPECT_GT(stops, 0);
}

}  // namespace
}  // namespace mg
