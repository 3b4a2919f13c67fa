#include "motiongraph/synthesis/rest_starts.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <vector>

#include "motiongraph/motion/forward_kinematics.h"
#include "synthesis/subject16_graph.h"

namespace mg {
namespace {

// The joints of database frame `frame` as the assembler plays it under `placement`.
std::vector<Vec3> joints_of(const MotionAssembler& assembler, int frame, const FloorTransform& placement = {}) {
  Motion motion = assembler.empty_motion();
  assembler.append_frame(frame, placement, motion);
  return world_positions(assembler.skeleton(), motion);
}

// The root mean square distance, over the window's sampled frames and the joints, between the
// coming frames' joints (one: the frame held) and the lead-in's placed by `alignment`: what rms_m
// says, computed plainly.
double placed_rms(const MotionAssembler& assembler, const std::vector<int>& coming, int first, int blend, int stride,
                  const FloorTransform& alignment) {
  const int samples = std::max(2, (blend + stride - 1) / stride);
  double sum = 0.0;
  size_t joints = 0;
  for (int t = 0; t < samples; ++t) {
    const std::vector<Vec3> h =
        joints_of(assembler, coming[std::min(static_cast<size_t>(t * stride), coming.size() - 1)]);
    const std::vector<Vec3> q = joints_of(assembler, first + t * stride, alignment);
    for (size_t j = 0; j < h.size(); ++j) sum += (h[j] - q[j]).squaredNorm();
    joints = h.size();
  }
  return std::sqrt(sum / (samples * static_cast<double>(joints)));
}

// Whether the motion at graph node `node` travels kStartTravelMps or faster over the kStartTravelS
// after it, as far as its clip goes.
bool node_travels(const SynthesisContext& context, int node) {
  const MotionDatabase& db = *context.db;
  const int from = context.graph->nodes[static_cast<size_t>(node)].frame;
  const DatabaseClip& clip = db.clips[static_cast<size_t>(db.clip_of(from))];
  const int to = std::min(clip.first_frame + clip.frame_count - 1,
                          from + static_cast<int>(std::lround(kStartTravelS * db.fps)));
  const Vec3 a = context.assembler.root_position(from, {}), b = context.assembler.root_position(to, {});
  return to > from && std::hypot(b.x() - a.x(), b.z() - a.z()) / ((to - from) / db.fps) >= kStartTravelMps;
}

// Motion under way: the first kStartBlendS of frames of each of subject 16's endings, from its
// node, as a rest taken back plays them on (find_starts_from).
std::vector<std::vector<int>> coming_windows(const SynthesisContext& context) {
  const int blend = static_cast<int>(std::lround(kStartBlendS * context.db->fps));
  std::vector<std::vector<int>> out;
  for (const RestEnding& ending : context.rest().endings) {
    std::vector<int> frames = ending.frames(*context.graph);
    if (static_cast<int>(frames.size()) < 2 * blend) continue;
    frames.resize(static_cast<size_t>(blend));
    out.push_back(frames);
  }
  return out;
}

// The frames subject 16's graph holds at rest: its endings' last frames.
std::vector<int> held_frames(const SynthesisContext& context) {
  std::vector<int> held;
  for (const RestEnding& ending : context.rest().endings) held.push_back(ending.last_frame);
  std::sort(held.begin(), held.end());
  held.erase(std::unique(held.begin(), held.end()), held.end());
  return held;
}

TEST(RestStarts, EachLeadsIntoTheFirstNodeAfterItsBlendWithinTheLongestLeadInWhereTheMotionTravels) {
  const SynthesisContext& context = test::subject16().context();
  const MotionGraph& graph = *context.graph;
  const MotionDatabase& db = *context.db;
  const int blend = static_cast<int>(std::lround(kStartBlendS * db.fps));
  const std::vector<int> held = held_frames(context);
  ASSERT_FALSE(held.empty());
  for (const int h : held) {
    const std::vector<RestStart> starts = find_rest_starts(db, graph, context.assembler, h);
    ASSERT_FALSE(starts.empty()) << h;
    EXPECT_LE(starts.size(), static_cast<size_t>(kStartChoices));
    std::vector<int> clips;
    for (size_t i = 0; i < starts.size(); ++i) {
      const RestStart& s = starts[i];
      const GraphNode& node = graph.nodes[static_cast<size_t>(s.node)];
      EXPECT_EQ(db.clip_of(s.first_frame), node.clip) << "the lead-in is the node's clip";
      EXPECT_EQ(s.blend_frames, blend);
      EXPECT_GE(s.frames(graph), blend);
      EXPECT_LE(s.frames(graph), std::lround(kMaxStartLeadS * db.fps));
      // No node of the clip between the blend's end and the node: the first after the blend.
      for (int n = 0; n < graph.node_count(); ++n) {
        const GraphNode& other = graph.nodes[static_cast<size_t>(n)];
        if (other.clip == node.clip && other.frame >= s.first_frame + blend) {
          EXPECT_GE(other.frame, node.frame) << "node " << n << " comes first";
        }
      }
      EXPECT_NEAR(s.rank_m, s.rms_m + kStartWaitMps * s.frames(graph) / db.fps, 1e-12);
      EXPECT_TRUE(node_travels(context, s.node)) << "a start into standing on";
      if (i > 0) {
        EXPECT_GE(s.rank_m, starts[i - 1].rank_m) << "best first";
      }
      clips.push_back(node.clip);
    }
    std::sort(clips.begin(), clips.end());
    EXPECT_EQ(std::adjacent_find(clips.begin(), clips.end()), clips.end()) << "one start per clip";
  }
}

// Every start's distance is the one its alignment gives, computed plainly; no small move of the
// alignment lowers it (the closed form is the optimum); placed by it, the lead-in's first frame
// stands where the frame held stands.
TEST(RestStarts, TheAlignmentIsTheBestAndPlacesTheLeadInOnTheFrameHeld) {
  const SynthesisContext& context = test::subject16().context();
  const MotionAssembler& assembler = context.assembler;
  const int stride = std::max(1, static_cast<int>(std::lround(context.db->fps / 30.0)));
  std::vector<std::vector<int>> windows = coming_windows(context);
  ASSERT_FALSE(windows.empty());
  windows.resize(std::min<size_t>(windows.size(), 3));
  for (const int h : held_frames(context)) windows.push_back({h});
  for (const std::vector<int>& coming : windows) {
    const int h = coming.front();
    const std::vector<RestStart> starts = find_starts_from(*context.db, *context.graph, assembler, coming);
    if (coming.size() == 1) {
      const std::vector<RestStart> held = find_rest_starts(*context.db, *context.graph, assembler, h);
      ASSERT_EQ(held.size(), starts.size());
      // (a frame held is the same window as that frame repeated over the blend)
      const std::vector<RestStart> repeated = find_starts_from(
          *context.db, *context.graph, assembler,
          std::vector<int>(static_cast<size_t>(std::lround(kStartBlendS * context.db->fps)), h));
      ASSERT_EQ(repeated.size(), starts.size());
      for (size_t i = 0; i < starts.size(); ++i) {
        EXPECT_EQ(held[i].first_frame, starts[i].first_frame);
        EXPECT_EQ(repeated[i].first_frame, starts[i].first_frame);
        EXPECT_NEAR(repeated[i].rms_m, starts[i].rms_m, 1e-9);
      }
    }
    for (const RestStart& s : starts) {
      const double rms = placed_rms(assembler, coming, s.first_frame, s.blend_frames, stride, s.alignment);
      ASSERT_NEAR(rms, s.rms_m, 1e-7) << h << " " << s.first_frame;
      for (const FloorTransform nudge : {FloorTransform{0.02, 0.0, 0.0}, FloorTransform{-0.02, 0.0, 0.0},
                                         FloorTransform{0.0, 0.01, 0.0}, FloorTransform{0.0, 0.0, -0.01}}) {
        FloorTransform moved = s.alignment;
        moved.yaw_rad += nudge.yaw_rad;
        moved.x_m += nudge.x_m;
        moved.z_m += nudge.z_m;
        EXPECT_GT(placed_rms(assembler, coming, s.first_frame, s.blend_frames, stride, moved), rms);
      }
    }
    // The nearest start's first frame stands where the first frame it comes from does, within its
    // distance (and the motion's travel over the blend).
    const RestStart& best = starts.front();
    const Vec3 held_root = assembler.root_position(h, {});
    const Vec3 lead_root = assembler.root_position(best.first_frame, best.alignment);
    const Vec3 coming_last = assembler.root_position(coming.back(), {});
    const double travel = std::hypot(coming_last.x() - held_root.x(), coming_last.z() - held_root.z());
    EXPECT_LT(std::hypot(held_root.x() - lead_root.x(), held_root.z() - lead_root.z()),
              3.0 * best.rms_m + travel + 0.02);
  }
}

// The starts kept are the best by rank of every clip's, found by brute force: every frame of every
// clip, its first node after the blend found by scanning the nodes (one where the motion travels),
// the floor alignment solved here (the 2D Procrustes problem: centroids and the angle of the
// cross-covariance).
TEST(RestStarts, AreTheBestClipsOfABruteForceSearch) {
  const SynthesisContext& context = test::subject16().context();
  const MotionGraph& graph = *context.graph;
  const MotionDatabase& db = *context.db;
  const int blend = static_cast<int>(std::lround(kStartBlendS * db.fps));
  const int max_lead = static_cast<int>(std::lround(kMaxStartLeadS * db.fps));
  const int stride = std::max(1, static_cast<int>(std::lround(db.fps / 30.0)));
  const int samples = std::max(2, (blend + stride - 1) / stride);
  std::map<int, std::vector<Vec3>> joints;  // per frame, as needed
  auto frame_joints = [&](int f) -> const std::vector<Vec3>& {
    auto it = joints.find(f);
    if (it == joints.end()) it = joints.emplace(f, joints_of(context.assembler, f)).first;
    return it->second;
  };
  // Whether the root of frame f travels slower than kStartTravelMps over kGoingS (to its clip's end).
  const int going_window = std::max(1, static_cast<int>(std::lround(kGoingS * db.fps)));
  auto slow = [&](int f) {
    const DatabaseClip& clip = db.clips[static_cast<size_t>(db.clip_of(f))];
    const int to = std::min(f + going_window, clip.first_frame + clip.frame_count - 1);
    const Vec3 a = context.assembler.root_position(f, {}), b = context.assembler.root_position(to, {});
    return std::hypot(b.x() - a.x(), b.z() - a.z()) < kStartTravelMps * going_window / db.fps;
  };
  // From the frame held at rest, and from a stopping clip under way (ranked by when it gets going
  // too, and not).
  ASSERT_FALSE(coming_windows(context).empty());
  const std::vector<int> under_way = coming_windows(context).front();
  const std::vector<std::pair<std::vector<int>, double>> windows = {
      {{held_frames(context).back()}, 0.0}, {under_way, 0.0}, {under_way, kGoingMps}};
  for (const auto& [coming, going_mps] : windows) {
    std::map<int, double> best;  // per clip with a lead-in, its best rank
    for (size_t c = 0; c < db.clips.size(); ++c) {
      const DatabaseClip& clip = db.clips[c];
      for (int f = clip.first_frame; f < clip.first_frame + clip.frame_count; f += stride) {
        int node = -1;
        for (int n = 0; n < graph.node_count() && node < 0; ++n) {
          const GraphNode& candidate = graph.nodes[static_cast<size_t>(n)];
          if (candidate.clip == static_cast<int>(c) && candidate.frame >= f + blend) node = n;
        }
        if (node < 0 || graph.nodes[static_cast<size_t>(node)].frame - f > max_lead) continue;
        if (!node_travels(context, node)) continue;
        const int last = graph.nodes[static_cast<size_t>(node)].frame;
        // Held points p, lead-in points q: centroids, then the yaw that turns q's spread onto p's.
        std::vector<Vec2> p, q;
        for (int t = 0; t < samples; ++t) {
          const std::vector<Vec3>& lead = frame_joints(std::min(f + t * stride, last));
          const std::vector<Vec3>& held =
              frame_joints(coming[std::min(static_cast<size_t>(t * stride), coming.size() - 1)]);
          for (size_t j = 0; j < held.size(); ++j) {
            p.emplace_back(held[j].x(), held[j].z());
            q.emplace_back(lead[j].x(), lead[j].z());
          }
        }
        Vec2 pc = Vec2::Zero(), qc = Vec2::Zero();
        for (size_t i = 0; i < p.size(); ++i) {
          pc += p[i] / static_cast<double>(p.size());
          qc += q[i] / static_cast<double>(q.size());
        }
        double a = 0.0, b = 0.0;
        for (size_t i = 0; i < p.size(); ++i) {
          const Vec2 u = p[i] - pc, v = q[i] - qc;
          a += u.x() * v.x() + u.y() * v.y();
          b += u.x() * v.y() - u.y() * v.x();
        }
        const double yaw = std::atan2(b, a);
        const FloorTransform turn{yaw, 0.0, 0.0};
        const Vec3 turned = turn.rotate(Vec3(qc.x(), 0.0, qc.y()));
        const FloorTransform alignment{yaw, pc.x() - turned.x(), pc.y() - turned.z()};
        const double rms = placed_rms(context.assembler, coming, f, blend, stride, alignment);
        int going = f;  // after the last slow frame before the node
        for (int g = f; g < last; ++g) going = slow(g) ? g + 1 : going;
        const double rank = rms + kStartWaitMps * (last - f) / db.fps + going_mps * (going - f) / db.fps;
        auto [it, added] = best.emplace(static_cast<int>(c), rank);
        if (!added) it->second = std::min(it->second, rank);
      }
    }
    std::vector<double> ranks;
    for (const auto& [clip, rank] : best) ranks.push_back(rank);
    std::sort(ranks.begin(), ranks.end());
    const std::vector<RestStart> starts = find_starts_from(db, graph, context.assembler, coming, going_mps);
    ASSERT_EQ(starts.size(), std::min(ranks.size(), static_cast<size_t>(kStartChoices)));
    for (size_t i = 0; i < starts.size(); ++i) {
      EXPECT_NEAR(starts[i].rank_m, ranks[i], 1e-7) << i;
      EXPECT_NEAR(starts[i].rank_m, best.at(graph.nodes[static_cast<size_t>(starts[i].node)].clip), 1e-7) << i;
    }
  }
}

}  // namespace
}  // namespace mg
