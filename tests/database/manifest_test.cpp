#include "motiongraph/database/manifest.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "test_data.h"

namespace mg {
namespace {

// Line numbers matter: the failing cases below expect errors on these lines.
constexpr const char* kManifest = R"(# test manifest
fps = 30
skeleton = "16.asf"
bvh_scale = 0.056444
input_fps = 120

[[clip]]
file = "16_15.amc"
name = "walk_a"
first_frame = 41
last_frame = 240
tags = ["walk"]
ranges = [
  { first_frame = 41, last_frame = 120, tags = ["start"] },
  { first_frame = 121, last_frame = 240, tags = ["steady", "walk"] },
]

[[clip]]
file = "../bvh/131_01.bvh"
bvh_scale = 0.01
input_fps = 120

[[clip.ranges]]
first_frame = 1
last_frame = 50
tags = ["start"]

[[clip]]
file = "16_35.AMC"
skeleton = "other/16.asf"
)";

TEST(Manifest, ReadsUpAxes) {
  auto manifest =
      parse_manifest("up_axis = \"Z\"\n[[clip]]\nfile = \"a.amc\"\n[[clip]]\nfile = \"b.bvh\"\nup_axis = \"y\"\n", "up.toml");
  ASSERT_TRUE(manifest) << manifest.error().to_string();
  EXPECT_EQ(manifest->up_axis, UpAxis::kZ);
  ASSERT_EQ(manifest->clips.size(), 2u);
  EXPECT_FALSE(manifest->clips[0].up_axis);
  EXPECT_EQ(manifest->clips[1].up_axis, UpAxis::kY);
}

TEST(Manifest, ReadsTravelSources) {
  auto manifest = parse_manifest(
      "travel = \"Feet\"\n[[clip]]\nfile = \"a.amc\"\n[[clip]]\nfile = \"b.bvh\"\ntravel = \"root\"\n", "t.toml");
  ASSERT_TRUE(manifest) << manifest.error().to_string();
  EXPECT_EQ(manifest->travel, TravelSource::kFeet);
  ASSERT_EQ(manifest->clips.size(), 2u);
  EXPECT_FALSE(manifest->clips[0].travel);
  EXPECT_EQ(manifest->clips[1].travel, TravelSource::kRoot);
}

TEST(Manifest, ReadsTheExample) {
  auto manifest = parse_manifest(kManifest, "db.toml");
  ASSERT_TRUE(manifest) << manifest.error().to_string();
  EXPECT_EQ(manifest->file_name, "db.toml");
  EXPECT_EQ(manifest->fps, 30.0);
  EXPECT_EQ(manifest->fps_line, 2);
  EXPECT_EQ(manifest->skeleton, "16.asf");
  EXPECT_EQ(manifest->skeleton_line, 3);
  EXPECT_EQ(manifest->bvh_scale, 0.056444);
  EXPECT_EQ(manifest->input_fps, 120.0);
  ASSERT_EQ(manifest->clips.size(), 3u);

  const ManifestClip& walk = manifest->clips[0];
  EXPECT_EQ(walk.file, "16_15.amc");
  EXPECT_EQ(walk.line, 7);
  EXPECT_EQ(walk.file_line, 8);
  EXPECT_EQ(walk.name, "walk_a");
  EXPECT_FALSE(walk.skeleton);
  EXPECT_EQ(walk.first_frame, 41);
  EXPECT_EQ(walk.last_frame, 240);
  EXPECT_EQ(walk.frames_line, 11);
  EXPECT_EQ(walk.tags, std::vector<std::string>{"walk"});
  ASSERT_EQ(walk.ranges.size(), 2u);
  EXPECT_EQ(walk.ranges[0].first_frame, 41);
  EXPECT_EQ(walk.ranges[0].last_frame, 120);
  EXPECT_EQ(walk.ranges[0].tags, std::vector<std::string>{"start"});
  EXPECT_EQ(walk.ranges[0].line, 14);
  EXPECT_EQ(walk.ranges[1].tags, (std::vector<std::string>{"steady", "walk"}));
  EXPECT_TRUE(walk.gives_tags());

  const ManifestClip& bvh = manifest->clips[1];
  EXPECT_EQ(bvh.file, "../bvh/131_01.bvh");
  EXPECT_EQ(bvh.bvh_scale, 0.01);
  EXPECT_EQ(bvh.input_fps, 120.0);
  EXPECT_FALSE(bvh.first_frame);
  EXPECT_FALSE(bvh.tags);
  EXPECT_FALSE(bvh.up_axis);
  EXPECT_FALSE(manifest->up_axis);
  ASSERT_EQ(bvh.ranges.size(), 1u);
  EXPECT_EQ(bvh.ranges[0].line, 23);
  EXPECT_TRUE(bvh.gives_tags());

  const ManifestClip& run = manifest->clips[2];
  EXPECT_EQ(run.skeleton, "other/16.asf");
  EXPECT_EQ(run.skeleton_line, 30);
  EXPECT_FALSE(run.gives_tags());  // left to the CMU index
}

TEST(Manifest, MinimalAndEmptyTags) {
  auto manifest = parse_manifest("[[clip]]\nfile = \"a.bvh\"\ntags = []\n", "m.toml");
  ASSERT_TRUE(manifest) << manifest.error().to_string();
  EXPECT_FALSE(manifest->fps);
  ASSERT_EQ(manifest->clips.size(), 1u);
  EXPECT_TRUE(manifest->clips[0].tags);
  EXPECT_TRUE(manifest->clips[0].tags->empty());
  EXPECT_TRUE(manifest->clips[0].gives_tags());  // "no tags", not "ask the CMU index"
}

TEST(Manifest, DuplicateTagsInAListCountOnce) {
  auto manifest = parse_manifest("[[clip]]\nfile = \"a.bvh\"\ntags = [\"walk\", \"walk\"]\n", "m.toml");
  ASSERT_TRUE(manifest) << manifest.error().to_string();
  EXPECT_EQ(manifest->clips[0].tags, std::vector<std::string>{"walk"});
}

TEST(Manifest, TagNames) {
  EXPECT_TRUE(is_valid_tag_name("walk"));
  EXPECT_TRUE(is_valid_tag_name("run-fast_2"));
  EXPECT_FALSE(is_valid_tag_name(""));
  EXPECT_FALSE(is_valid_tag_name("fast walk"));
  EXPECT_FALSE(is_valid_tag_name("walk,run"));
}

TEST(Manifest, OneCleanErrorPerRule) {
  const std::string base = kManifest;
  const auto r = [&](const std::string& from, const std::string& to) { return test::replace_once(base, from, to); };
  // The line after the manifest's last ([feet] appended there).
  const int end = static_cast<int>(std::count(base.begin(), base.end(), '\n')) + 1;
  const std::vector<test::ErrorCase> cases = {
      {"TOML syntax", r("fps = 30", "fps = = 30"), 2, "TOML"},
      {"unknown top-level key", r("fps = 30", "fsp = 30"), 2, "unknown key 'fsp' at the top level"},
      {"unknown clip key", r("first_frame = 41\n", "frist_frame = 41\n"), 10, "unknown key 'frist_frame' in a [[clip]]"},
      {"unknown range key", r("tags = [\"start\"] }", "tag = [\"start\"] }"), 14, "unknown key 'tag' in a range"},
      {"fps not a number", r("fps = 30", "fps = \"30\""), 2, "'fps' must be a number"},
      {"fps not positive", r("fps = 30", "fps = 0"), 2, "positive"},
      {"fps not finite", r("fps = 30", "fps = inf"), 2, "positive"},
      {"fps under build's least", r("fps = 30", "fps = 0.5"), 2, "'fps' must be 1 to 1000, not 0.5"},
      {"fps over build's most", r("fps = 30", "fps = 2000"), 2, "'fps' must be 1 to 1000, not 2000"},
      {"default bvh_scale not positive", r("bvh_scale = 0.056444", "bvh_scale = -1"), 4, "positive"},
      {"keep_rest_frames not a boolean", r("input_fps = 120\n\n[[clip]]\nfile = \"16_15.amc\"",
                                          "keep_rest_frames = 1\n\n[[clip]]\nfile = \"16_15.amc\""), 5,
       "'keep_rest_frames' must be true or false, not an integer"},
      {"clip bvh_scale past a unit's range", r("bvh_scale = 0.01", "bvh_scale = 1e9"), 20,
       "'bvh_scale' must lie between 1e-06 and 1e+06 metres per unit, not 1e+09"},
      {"clip input_fps not positive", r("input_fps = 120\n\n[[clip.ranges]]", "input_fps = 0\n\n[[clip.ranges]]"), 21,
       "'input_fps' must be a positive number"},
      {"skeleton not a string", r("skeleton = \"16.asf\"", "skeleton = 16"), 3, "'skeleton' must be a string"},
      {"no clips", "fps = 30\n", 0, "names no clips"},
      {"clip not an array of tables", "fps = 30\n[clip]\nfile = \"a.amc\"\n", 2, "write each clip as [[clip]]"},
      {"clip without file", r("file = \"16_15.amc\"", "# no file"), 7, "needs a file"},
      {"file empty", r("file = \"16_15.amc\"", "file = \"\""), 8, "must not be empty"},
      {"file not a string", r("file = \"16_15.amc\"", "file = 1615"), 8, "'file' must be a string"},
      {"file neither AMC nor BVH", r("file = \"16_15.amc\"", "file = \"16_15.txt\""), 8, "is not .amc, .bvh, .glb, .gltf or .fbx"},
      {"animation of an AMC clip", r("file = \"16_15.amc\"", "file = \"16_15.amc\"\nanimation = \"walk\""), 9,
       "'animation' applies to glTF and FBX clips only"},
      {"name empty", r("name = \"walk_a\"", "name = \"\""), 9, "must not be empty"},
      {"skeleton on a BVH clip", r("input_fps = 120\n\n[[clip.ranges]]", "skeleton = \"x.asf\"\n\n[[clip.ranges]]"),
       21, "AMC clips only"},
      {"bvh_scale on an AMC clip", r("name = \"walk_a\"", "bvh_scale = 1"), 9, "BVH clips only"},
      {"default up_axis not y or z", r("bvh_scale = 0.056444", "up_axis = \"x\""), 4,
       "'up_axis' must be \"y\" or \"z\""},
      {"clip up_axis not a string", r("bvh_scale = 0.01", "up_axis = 2"), 20, "'up_axis' must be a string"},
      {"default travel unknown", r("bvh_scale = 0.056444", "travel = \"hips\""), 4,
       "'travel' must be \"auto\", \"root\" or \"feet\", not \"hips\""},
      {"clip travel not a string", r("bvh_scale = 0.01", "travel = true"), 20, "'travel' must be a string"},
      {"first_frame below 1", r("first_frame = 41\n", "first_frame = 0\n"), 10, "numbered from 1"},
      {"first_frame not an integer", r("first_frame = 41\n", "first_frame = 40.5\n"), 10, "integer frame number"},
      {"last_frame before first_frame", r("last_frame = 240\n", "last_frame = 40\n"), 11, "comes before first_frame"},
      {"range without last_frame", r("first_frame = 41, last_frame = 120,", "first_frame = 41,"), 14, "needs both"},
      {"range last before first", r("last_frame = 120,", "last_frame = 30,"), 14, "comes before its first_frame"},
      {"range before the clip", r("{ first_frame = 41,", "{ first_frame = 40,"), 14, "before the clip's first_frame"},
      {"range after the clip", r("last_frame = 240, tags", "last_frame = 241, tags"), 15, "after the clip's last_frame"},
      {"range without tags", r("tags = [\"start\"]\n", "# no tags\n"), 23, "a range needs tags"},
      {"range with no tag", r("tags = [\"start\"]\n", "tags = []\n"), 26, "at least one tag"},
      {"tags not an array", r("tags = [\"walk\"]", "tags = \"walk\""), 12, "array of strings"},
      {"tag not a string", r("tags = [\"walk\"]", "tags = [1]"), 12, "a tag must be a string"},
      {"tag name invalid", r("tags = [\"walk\"]", "tags = [\"fast walk\"]"), 12, "not a valid name"},
      {"ranges not tables", r("skeleton = \"other/16.asf\"", "ranges = [1, 2]"), 30, "array of tables"},
      {"feet not a table", r("fps = 30", "fps = 30\nfeet = \"lfoot\""), 3, "'feet' must be a table"},
      {"unknown key in [feet]", base + "[feet]\nleft_heel = \"lfoot\"\n", end + 1, "unknown key 'left_heel' in [feet]"},
      {"foot name not a string", base + "[feet]\nleft_ankle = 3\n", end + 1, "'left_ankle' must be a string"},
      {"one joint for both ankles", base + "[feet]\nleft_ankle = \"Foot\"\nright_ankle = \"foot\"\n", end,
       "both named"},
  };
  for (const auto& c : cases) {
    auto manifest = parse_manifest(c.text, "bad.toml");
    ASSERT_FALSE(manifest) << c.rule;
    EXPECT_EQ(manifest.error().file, "bad.toml") << c.rule;
    test::expect_error_matches(manifest.error(), c);
  }
}

TEST(Manifest, FeetNameTheFootJointsAnyLeftOutFound) {
  auto manifest = parse_manifest(
      "[feet]\nleft_ankle = \"LeftAnkle\"\nright_ankle = \"RightAnkle\"\nright_toe = \"RightToe\"\n"
      "[[clip]]\nfile = \"a.bvh\"\n",
      "feet.toml");
  ASSERT_TRUE(manifest) << manifest.error().to_string();
  ASSERT_TRUE(manifest->feet);
  EXPECT_EQ(*manifest->feet, (FootJointNames{"LeftAnkle", "", "RightAnkle", "RightToe"}));
  EXPECT_EQ(manifest->feet_line, 1);
  auto none = parse_manifest("[[clip]]\nfile = \"a.bvh\"\n", "none.toml");
  ASSERT_TRUE(none);
  EXPECT_FALSE(none->feet);
}

TEST(Manifest, EveryPrefixFailsCleanlyOrParses) {
  const std::string text = kManifest;
  const int line_count = static_cast<int>(std::count(text.begin(), text.end(), '\n')) + 1;
  for (size_t n = 0; n <= text.size(); ++n) {
    auto manifest = parse_manifest(text.substr(0, n), "cut.toml");
    if (manifest) continue;
    EXPECT_GE(manifest.error().line, 0) << n;
    EXPECT_LE(manifest.error().line, line_count) << n;
    EXPECT_FALSE(manifest.error().message.empty()) << n;
  }
}

}  // namespace
}  // namespace mg
