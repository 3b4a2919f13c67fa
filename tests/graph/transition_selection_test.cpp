// Per-motion-type thresholds, checked from their definition: each tag keeps the share of its
// own candidates that the database keeps of all candidates under the global threshold; or, when
// given (the automatic choice's), each candidate of a tag passes at or below the tag's own.
#include "motiongraph/graph/transition_selection.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "motiongraph/metric/pair_alignment.h"
#include "test_data.h"

namespace mg {
namespace {

// Walking (16_15, 16_17) and running (16_35): running's distances are larger.
struct WalkAndRun {
  MotionDatabase db;
  int walk = 0, run = 0;
  std::optional<FrameFeatures> features;
  std::optional<CandidateSearch> search;
  std::vector<TagMask> frame_tags;
  TagMask tags = 0;

  // Whether all 2k frames of t's two windows carry the tag.
  bool belongs(const Transition& t, int tag) const {
    const int k = features->window;
    for (int f = t.from_frame; f < t.from_frame + k; ++f) if (!(frame_tags[f] >> tag & 1)) return false;
    for (int f = t.to_frame - k + 1; f <= t.to_frame; ++f) if (!(frame_tags[f] >> tag & 1)) return false;
    return true;
  }
};

const WalkAndRun& walk_and_run() {
  static const WalkAndRun x = [] {
    WalkAndRun l;
    l.db = test::small_database({"cmu/16/16_15.amc", "cmu/16/16_35.amc", "cmu/16/16_17.amc"});
    l.walk = l.db.tag_index("walk");
    l.run = l.db.tag_index("run");
    for (int c : {0, 2}) l.db.tag_ranges.push_back({l.walk, l.db.clips[c].first_frame, l.db.clips[c].frame_count});
    l.db.tag_ranges.push_back({l.run, l.db.clips[1].first_frame, l.db.clips[1].frame_count});
    DistanceSettings distance;
    auto layout = make_cloud_layout(l.db.skeletons[0], {});
    auto features = make_frame_features(l.db, *layout, distance);
    EXPECT_TRUE(features.ok());
    if (!features) return l;
    l.features = std::move(*features);
    auto search = find_candidates(*l.features, distance, {});
    EXPECT_TRUE(search.ok());
    if (search) l.search = std::move(*search);
    l.frame_tags = l.db.frame_tags();
    l.tags = (TagMask{1} << l.walk) | (TagMask{1} << l.run);
    return l;
  }();
  return x;
}

TEST(TransitionSelection, EachTagKeepsTheDatabasesShareOfItsOwnCandidates) {
  const WalkAndRun& l = walk_and_run();
  ASSERT_TRUE(l.features && l.search);
  const MotionDatabase& db = l.db;
  const int run = l.run;
  const FrameFeatures* features = &*l.features;
  const CandidateSearch* search = &*l.search;
  const std::vector<TagMask>& frame_tags = l.frame_tags;
  const TagMask tags = l.tags;
  TransitionSettings settings;
  settings.locality_radius = 0;  // keep every candidate that passes, to count them exactly
  auto one = select_transitions(*features, *search, [&] { auto s = settings; s.per_tag_thresholds = false; return s; }(),
                                frame_tags, tags);
  auto per_tag = select_transitions(*features, *search, settings, frame_tags, tags);
  ASSERT_TRUE(one.ok() && per_tag.ok());
  EXPECT_TRUE(one->tag_thresholds.empty());
  EXPECT_EQ(per_tag->threshold, one->threshold);
  auto belongs = [&](const Transition& t, int tag) { return l.belongs(t, tag); };
  const double share = static_cast<double>(std::count_if(search->minima.begin(), search->minima.end(),
                                                         [&](const Transition& t) { return t.distance <= one->threshold; })) /
                       static_cast<double>(search->minima.size());
  ASSERT_EQ(per_tag->tag_thresholds.size(), 2u);
  for (const TagThreshold& own : per_tag->tag_thresholds) {
    std::vector<float> d;
    for (const Transition& t : search->minima) if (belongs(t, own.tag)) d.push_back(t.distance);
    ASSERT_EQ(own.candidates, static_cast<int>(d.size()));
    std::sort(d.begin(), d.end());
    const size_t rank = static_cast<size_t>(std::ceil(share * static_cast<double>(d.size())));
    const double expected = rank == 0 ? 0.0 : d[rank - 1];
    EXPECT_DOUBLE_EQ(own.threshold, std::max(expected, per_tag->threshold)) << db.tag_names[own.tag];
  }
  // Running's own threshold is above the global one, and it adds run-run transitions.
  const auto run_threshold = std::find_if(per_tag->tag_thresholds.begin(), per_tag->tag_thresholds.end(),
                                          [&](const TagThreshold& t) { return t.tag == run; });
  ASSERT_NE(run_threshold, per_tag->tag_thresholds.end());
  EXPECT_GT(run_threshold->threshold, per_tag->threshold);
  auto count_run = [&](const TransitionSelection& s) {
    return std::count_if(s.transitions.begin(), s.transitions.end(), [&](const Transition& t) { return belongs(t, run); });
  };
  EXPECT_GT(count_run(*per_tag), count_run(*one));
  // Every kept transition passes the global threshold or the threshold of a tag it belongs to.
  for (const Transition& t : per_tag->transitions) {
    bool passes = t.distance <= per_tag->threshold;
    for (const TagThreshold& own : per_tag->tag_thresholds) passes |= belongs(t, own.tag) && t.distance <= own.threshold;
    EXPECT_TRUE(passes) << t.from_frame << "->" << t.to_frame;
  }
}

TEST(TransitionSelection, UnalignedSelectsTheSameTransitionsWithoutTheirAlignments) {
  const WalkAndRun& l = walk_and_run();
  ASSERT_TRUE(l.features && l.search);
  TransitionSettings settings;
  settings.threshold_quantile = 0.05;
  auto aligned = select_transitions(*l.features, *l.search, settings, l.frame_tags, l.tags);
  auto shape = select_transitions(*l.features, *l.search, settings, l.frame_tags, l.tags, false);
  ASSERT_TRUE(aligned && shape);
  ASSERT_EQ(aligned->transitions.size(), shape->transitions.size());
  ASSERT_GT(aligned->transitions.size(), 10u);
  int turned = 0;
  for (size_t i = 0; i < shape->transitions.size(); ++i) {
    const Transition &a = aligned->transitions[i], &b = shape->transitions[i];
    EXPECT_EQ(a.from_frame, b.from_frame);
    EXPECT_EQ(a.to_frame, b.to_frame);
    EXPECT_EQ(a.distance, b.distance);
    EXPECT_EQ(b.yaw_rad, 0.0f);
    EXPECT_EQ(b.x_m, 0.0f);
    EXPECT_EQ(b.z_m, 0.0f);
    const FloorAlignment want = align_pair(*l.features, a.from_frame, a.to_frame);
    EXPECT_EQ(a.yaw_rad, static_cast<float>(want.yaw_rad));
    EXPECT_EQ(a.x_m, static_cast<float>(want.x_m));
    turned += std::abs(a.yaw_rad) > 1e-3f ? 1 : 0;
  }
  EXPECT_GT(turned, 0);
}

TEST(TransitionSelection, GivenTagThresholdsAreWhatACandidateOfTheTagPasses) {
  const WalkAndRun& l = walk_and_run();
  ASSERT_TRUE(l.features && l.search);
  const MotionDatabase& db = l.db;
  const int walk = l.walk, run = l.run;
  const FrameFeatures* features = &*l.features;
  const CandidateSearch* search = &*l.search;
  const std::vector<TagMask>& frame_tags = l.frame_tags;
  const TagMask tags = l.tags;
  auto belongs = [&](const Transition& t, int tag) { return l.belongs(t, tag); };
  std::vector<float> d;
  for (const Transition& t : search->minima) d.push_back(t.distance);
  std::sort(d.begin(), d.end());
  const double global = d[d.size() / 10], low = d[d.size() / 20];
  double high = 0.0;  // running's own: its largest candidate, above the global threshold
  for (const Transition& t : search->minima) {
    if (belongs(t, run)) high = std::max(high, static_cast<double>(t.distance));
  }
  ASSERT_GT(high, global);
  // Run's own above the global threshold; walk's below it (lifted to it); and run's alone.
  for (const std::vector<OwnThreshold>& given : {std::vector<OwnThreshold>{{run, high}, {walk, low}},
                                                 std::vector<OwnThreshold>{{run, high}}}) {
    TransitionSettings settings;
    settings.locality_radius = 0;  // keep every candidate that passes, to count them exactly
    settings.threshold = global;
    settings.tag_thresholds = given;
    auto selected = select_transitions(*features, *search, settings, frame_tags, tags);
    ASSERT_TRUE(selected) << selected.error().to_string();
    ASSERT_EQ(selected->tag_thresholds.size(), given.size());
    for (const TagThreshold& own : selected->tag_thresholds) {
      EXPECT_TRUE(own.given);
      EXPECT_DOUBLE_EQ(own.threshold, own.tag == run ? high : global) << db.tag_names[own.tag];
      EXPECT_EQ(own.candidates,
                std::count_if(search->minima.begin(), search->minima.end(),
                              [&](const Transition& t) { return belongs(t, own.tag); }));
    }
    size_t passing = 0;
    for (const Transition& t : search->minima) {
      const bool passes = t.distance <= global || (belongs(t, run) && t.distance <= high);
      passing += passes ? 1 : 0;
      const bool kept =
          std::any_of(selected->transitions.begin(), selected->transitions.end(),
                      [&](const Transition& x) { return x.from_frame == t.from_frame && x.to_frame == t.to_frame; });
      EXPECT_EQ(kept, passes) << t.from_frame << "->" << t.to_frame;
    }
    EXPECT_EQ(selected->transitions.size(), passing);
    EXPECT_GT(passing, static_cast<size_t>(std::count_if(d.begin(), d.end(), [&](float x) { return x <= global; })));
  }
  // Given for the frames of none of the tags (here: walk only, so running is untagged).
  TransitionSettings untagged;
  untagged.locality_radius = 0;
  untagged.threshold = global;
  untagged.tag_thresholds = {{-1, high}};
  const TagMask walk_only = TagMask{1} << walk;
  auto selected = select_transitions(*features, *search, untagged, frame_tags, walk_only);
  ASSERT_TRUE(selected) << selected.error().to_string();
  ASSERT_EQ(selected->tag_thresholds.size(), 1u);
  EXPECT_EQ(selected->tag_thresholds[0].tag, -1);
  size_t passing = 0;
  for (const Transition& t : search->minima) passing += t.distance <= global || (belongs(t, run) && t.distance <= high);
  EXPECT_EQ(selected->transitions.size(), passing);
  EXPECT_EQ(selected->tag_thresholds[0].candidates,
            std::count_if(search->minima.begin(), search->minima.end(),
                          [&](const Transition& t) { return belongs(t, run); }));
  // The settings' JSON keeps them.
  TransitionSettings settings;
  settings.tag_thresholds = {{run, high}, {walk, low}};
  const TransitionSettings back = nlohmann::json(settings).get<TransitionSettings>();
  EXPECT_EQ(back.tag_thresholds, settings.tag_thresholds);
  EXPECT_TRUE(nlohmann::json(TransitionSettings{}).get<TransitionSettings>().tag_thresholds.empty());
  settings.tag_thresholds = {{run, -1.0}};
  EXPECT_FALSE(settings.validate());
}

}  // namespace
}  // namespace mg
