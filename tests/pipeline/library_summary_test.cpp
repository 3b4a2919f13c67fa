#include "motiongraph/pipeline/library_summary.h"

#include <map>
#include <set>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "motiongraph/database/database_contacts.h"
#include "motiongraph/motion/clip_summary.h"
#include "test_data.h"

namespace mg {
namespace {

// Three bundled clips back to back at 30 fps, with tags laid over them by hand: two walk
// ranges that overlap inside the first clip, a run range across the first two clips' boundary,
// the third clip untagged.
MotionDatabase tagged_database() {
  MotionDatabase db = test::small_database({"cmu/16/16_15.amc", "cmu/16/16_57.amc", "cmu/16/16_01.amc"});
  db.skeleton_names = {"16.asf"};
  db.tag_names = {"walk", "run"};
  const DatabaseClip& first = db.clips[0];
  const DatabaseClip& second = db.clips[1];
  db.tag_ranges = {{0, 0, 30}, {0, 20, 40}, {1, first.frame_count - 10, 25}, {0, first.frame_count - 5, 5}};
  EXPECT_LT(25 - 10, second.frame_count);
  return db;
}

// Each tag's frames of each clip, counted frame by frame from the ranges.
std::map<std::pair<size_t, int>, std::set<int>> frames_by_clip_and_tag(const MotionDatabase& db) {
  std::map<std::pair<size_t, int>, std::set<int>> frames;
  for (size_t c = 0; c < db.clips.size(); ++c) {
    const DatabaseClip& clip = db.clips[c];
    for (const TagRange& range : db.tag_ranges) {
      for (int f = range.first_frame; f < range.first_frame + range.frame_count; ++f) {
        if (f >= clip.first_frame && f < clip.first_frame + clip.frame_count) {
          frames[{c, range.tag}].insert(f - clip.first_frame);
        }
      }
    }
  }
  return frames;
}

TEST(LibrarySummary, TagRunsMergeOverlapsAndStopAtClipEnds) {
  const MotionDatabase db = tagged_database();
  const LibrarySummary s = summarize_library(db, {}, false);
  ASSERT_EQ(s.clip_tags.size(), 3u);
  const int first_frames = db.clips[0].frame_count;
  // Walk 0-29 and 20-59 are one run 0-59; walk over the last 5 frames is another; run over the
  // last 10 frames of the first clip, and the first 15 of the second.
  const std::vector<std::tuple<std::string, int, int>> first = {
      {"walk", 0, 60}, {"walk", first_frames - 5, 5}, {"run", first_frames - 10, 10}};
  ASSERT_EQ(s.clip_tags[0].size(), first.size());
  for (size_t i = 0; i < first.size(); ++i) {
    EXPECT_EQ(s.clip_tags[0][i].tag, std::get<0>(first[i]));
    EXPECT_EQ(s.clip_tags[0][i].first_frame, std::get<1>(first[i]));
    EXPECT_EQ(s.clip_tags[0][i].frame_count, std::get<2>(first[i]));
  }
  ASSERT_EQ(s.clip_tags[1].size(), 1u);
  EXPECT_EQ(s.clip_tags[1][0].tag, "run");
  EXPECT_EQ(s.clip_tags[1][0].first_frame, 0);
  EXPECT_EQ(s.clip_tags[1][0].frame_count, 15);
  EXPECT_TRUE(s.clip_tags[2].empty());
  EXPECT_EQ(clip_tags_text(s.clip_tags[0], first_frames),
            fmt::format("walk 0-59, walk {}-{}, run {}-{}", first_frames - 5, first_frames - 1, first_frames - 10,
                        first_frames - 1));
  EXPECT_EQ(clip_tags_text(s.clip_tags[1], 15), "run");
  EXPECT_EQ(clip_tags_text(s.clip_tags[2], db.clips[2].frame_count), "-");
}

TEST(LibrarySummary, TotalsAreTheFramesUnderEachTagCountedOnce) {
  const MotionDatabase db = tagged_database();
  const LibrarySummary s = summarize_library(db, {}, false);
  std::map<std::string, TagTotal> want;
  for (const auto& [key, frames] : frames_by_clip_and_tag(db)) {
    TagTotal& total = want[db.tag_names[static_cast<size_t>(key.second)]];
    total.clips += 1;
    total.frames += static_cast<int>(frames.size());
  }
  ASSERT_EQ(s.tags.size(), want.size());
  for (const auto& [tag, total] : want) {
    EXPECT_EQ(s.tags.at(tag).clips, total.clips) << tag;
    EXPECT_EQ(s.tags.at(tag).frames, total.frames) << tag;
  }
  EXPECT_EQ(s.untagged.clips, 1);
  EXPECT_EQ(s.untagged.frames, db.clips[2].frame_count);
  for (size_t c = 0; c < db.clips.size(); ++c) {
    EXPECT_DOUBLE_EQ(s.clip_travel_m[c], summarize(db.skeletons[0], db.clips[c].motion).root_path_m);
  }
}

TEST(LibrarySummary, FeetFoundOrWhyNotAndSkeletonFilesOnce) {
  MotionDatabase db = tagged_database();
  db.skeletons.push_back(db.skeletons[0]);
  db.skeleton_names = {"16.asf", "16.asf"};  // one file read two ways
  db.clips[1].skeleton = 1;
  db.contacts_error = "no joint named like a left ankle";
  LibrarySummary s = summarize_library(db, {}, false);
  EXPECT_EQ(s.skeleton_files, std::vector<std::string>{"16.asf"});
  EXPECT_FALSE(s.feet.has_value());
  EXPECT_EQ(s.feet_missing, "no joint named like a left ankle");
  const nlohmann::json missing = library_summary_json(std::vector<std::string>{"lib"}, db, s);
  EXPECT_EQ(missing["feet"]["missing"], "no joint named like a left ankle");
  EXPECT_TRUE(missing["feet"]["source"].is_null());

  ASSERT_TRUE(find_database_contacts(db).ok());
  s = summarize_library(db, {}, true);
  ASSERT_TRUE(s.feet.has_value());
  EXPECT_EQ(s.feet_source, "--feet");
  EXPECT_EQ(db.skeletons[0].joint(s.feet->left.ankle).name, "lfoot");
  const nlohmann::json found = library_summary_json(std::vector<std::string>{"lib"}, db, s);
  EXPECT_EQ(found["feet"]["left"]["ankle"], "lfoot");
  EXPECT_EQ(found["feet"]["right"]["toe"], "rtoes");
  db.foot_names.left_ankle = "lfoot";
  EXPECT_EQ(summarize_library(db, {}, false).feet_source, "the manifest's [feet]");
}

TEST(LibrarySummary, JsonCarriesTheClipsAndWhatLoadingChose) {
  const MotionDatabase db = tagged_database();
  DatabaseLoadNotes notes;
  LengthUnitChoice cm;
  cm.unit = {"cm", 0.01};
  cm.figure_size_units = 171.0;
  cm.figure_size_m = 1.71;
  cm.plausible = true;
  notes.detected_units.push_back({"walk.bvh", cm});
  UpAxisChoice lying;
  lying.axis = UpAxis::kY;
  lying.animation_ratio = 0.4;
  lying.rest_ratio = 3.0;
  notes.detected_up_axes.push_back({"crawl.bvh", lying, UpAxis::kZ});
  InPlaceChoice in_place;
  in_place.in_place = in_place.recovered = true;
  in_place.recovered_m = 3.5;
  in_place.slide_speed_m_s = 0.8;
  notes.recovered_travels.push_back({"loop.bvh", TravelSource::kAuto, in_place});
  notes.matched_rigs.push_back({"max.bvh", {{"LeftHip", "lfemur"}}, RestPoseDifference{90.0, "lradius"}});
  notes.matched_rigs.push_back({"builder.bvh", {{"LeftUpLeg", "lfemur"}}, std::nullopt});
  ClipDoubts floating;
  floating.floor = {"its lowest joint stays 0.50-0.60 m above the floor (y = 0)"};
  notes.clip_doubts.push_back({db.clips[2].name, floating, {}});
  const LibrarySummary s = summarize_library(db, notes, false);
  const nlohmann::json doc = library_summary_json(std::vector<std::string>{"a", "b"}, db, s);

  EXPECT_EQ(doc["inputs"], (nlohmann::json{"a", "b"}));
  EXPECT_EQ(doc["frames"], db.frame_count());
  EXPECT_DOUBLE_EQ(doc["duration_s"].get<double>(), db.frame_count() / 30.0);
  EXPECT_EQ(doc["untagged"]["clips"], 1);
  EXPECT_EQ(doc["tags"]["walk"]["frames"], s.tags.at("walk").frames);
  ASSERT_EQ(doc["clips"].size(), 3u);
  EXPECT_EQ(doc["clips"][1]["tag_ranges"],
            (nlohmann::json::array({{{"tag", "run"}, {"first_frame", 0}, {"frames", 15}}})));
  EXPECT_EQ(doc["clips"][1]["tags"], (nlohmann::json{"run"}));
  EXPECT_DOUBLE_EQ(doc["clips"][2]["root_path_m"].get<double>(), s.clip_travel_m[2]);
  EXPECT_EQ(doc["warnings"], nlohmann::json(load_warnings(notes)));
  ASSERT_EQ(doc["warnings"].size(), 4u);  // the file read in the library's axis, two rigs, the doubt
  EXPECT_EQ(doc["warnings"][3], clip_doubt_line(db.clips[2].name, floating));
  // Each clip carries its own doubts: the third the floor's phrase, the others none.
  EXPECT_EQ(doc["clips"][2]["doubts"], nlohmann::json(floating.phrases()));
  EXPECT_EQ(doc["clips"][0]["doubts"], nlohmann::json::array());
  const nlohmann::json& reading = doc["reading"];
  EXPECT_EQ(reading["units"], (nlohmann::json::array({{{"file", "walk.bvh"},
                                                         {"unit", "cm"},
                                                         {"metres_per_unit", 0.01},
                                                         {"figure_m", 1.71},
                                                         {"plausible", true},
                                                         {"also", nullptr}}})));
  ASSERT_EQ(reading["up_axes"].size(), 1u);
  EXPECT_EQ(reading["up_axes"][0]["axis"], "z");  // read in the library's axis
  EXPECT_EQ(reading["up_axes"][0]["own_axis"], "y");
  EXPECT_EQ(reading["up_axes"][0]["rest_ratio"], 3.0);
  ASSERT_EQ(reading["travel_recovered"].size(), 1u);
  EXPECT_EQ(reading["travel_recovered"][0]["file"], "loop.bvh");
  EXPECT_EQ(reading["travel_recovered"][0]["recovered_m"], 3.5);
  EXPECT_EQ(reading["travel_recovered"][0]["in_place"], true);
  EXPECT_EQ(reading["rigs"], (nlohmann::json::array(
                                 {{{"file", "max.bvh"},
                                   {"renamed", nlohmann::json::array({nlohmann::json::array({"LeftHip", "lfemur"})})},
                                   {"rest_pose", {{"bone", "lradius"}, {"angle_deg", 90.0}}}},
                                  {{"file", "builder.bvh"},
                                   {"renamed", nlohmann::json::array({nlohmann::json::array({"LeftUpLeg", "lfemur"})})},
                                   {"rest_pose", nullptr}}})));
}

}  // namespace
}  // namespace mg
