// Per-motion-type thresholds, checked from their definition: each tag keeps the share of its
// own candidates that the database keeps of all candidates under the global threshold.
#include "motiongraph/graph/transition_selection.h"

#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "test_data.h"

namespace mg {
namespace {

TEST(TransitionSelection, EachTagKeepsTheDatabasesShareOfItsOwnCandidates) {
  // Walking (16_15, 16_17) and running (16_35): running's distances are larger.
  MotionDatabase db = test::small_database({"cmu/16/16_15.amc", "cmu/16/16_35.amc", "cmu/16/16_17.amc"});
  const int walk = db.tag_index("walk"), run = db.tag_index("run");
  for (int c : {0, 2}) db.tag_ranges.push_back({walk, db.clips[c].first_frame, db.clips[c].frame_count});
  db.tag_ranges.push_back({run, db.clips[1].first_frame, db.clips[1].frame_count});
  DistanceSettings distance;
  auto layout = make_cloud_layout(db.skeletons[0], {});
  auto features = make_frame_features(db, *layout, distance);
  ASSERT_TRUE(features.ok());
  auto search = find_candidates(*features, distance, {});
  ASSERT_TRUE(search.ok());
  const std::vector<TagMask> frame_tags = db.frame_tags();
  const TagMask tags = (TagMask{1} << walk) | (TagMask{1} << run);
  TransitionSettings settings;
  settings.locality_radius = 0;  // keep every candidate that passes, to count them exactly
  auto one = select_transitions(*features, *search, [&] { auto s = settings; s.per_tag_thresholds = false; return s; }(),
                                frame_tags, tags);
  auto per_tag = select_transitions(*features, *search, settings, frame_tags, tags);
  ASSERT_TRUE(one.ok() && per_tag.ok());
  EXPECT_TRUE(one->tag_thresholds.empty());
  EXPECT_EQ(per_tag->threshold, one->threshold);

  const int k = features->window;
  auto belongs = [&](const Transition& t, int tag) {
    for (int f = t.from_frame; f < t.from_frame + k; ++f) if (!(frame_tags[f] >> tag & 1)) return false;
    for (int f = t.to_frame - k + 1; f <= t.to_frame; ++f) if (!(frame_tags[f] >> tag & 1)) return false;
    return true;
  };
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

}  // namespace
}  // namespace mg
