#include "motiongraph/database/database_loader.h"

#include <algorithm>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <gtest/gtest.h>

#include "motion/cycle_loop.h"
#include "motion/glitched.h"
#include "motion/max_apart.h"
#include "motion/static_root_bvh.h"
#include "motiongraph/database/database_contacts.h"
#include "motiongraph/export/bvh_writer.h"
#include "motiongraph/export/gltf_writer.h"
#include "motiongraph/io/file.h"
#include "motiongraph/motion/common_joints.h"
#include "motiongraph/motion/forward_kinematics.h"
#include "motiongraph/motion/length_unit.h"
#include "motiongraph/motion/mirror.h"
#include "motiongraph/motion/resample.h"
#include "motiongraph/motion/rig_matching.h"
#include "motiongraph/motion/root_motion.h"
#include "motiongraph/motion/up_axis.h"
#include "motiongraph/synthesis/facing.h"
#include "temp_folder.h"
#include "test_data.h"

namespace mg {
namespace {

namespace fs = std::filesystem;

const std::vector<std::string> kSubject16 = {"16_01", "16_05", "16_11", "16_13", "16_15", "16_16", "16_17", "16_19",
                                             "16_33", "16_35", "16_37", "16_39", "16_41", "16_43", "16_57"};

DatabaseSettings cmu_settings() {
  DatabaseSettings settings;
  settings.cmu_index_path = test::data_path("cmu/cmu-mocap-index.tsv");
  return settings;
}

using test::TempFolder;

std::set<std::string> tags_of(const MotionDatabase& db, int clip) {
  std::set<std::string> tags;
  const DatabaseClip& c = db.clips[static_cast<size_t>(clip)];
  for (const TagRange& range : db.tag_ranges) {
    if (range.first_frame == c.first_frame && range.frame_count == c.frame_count) {
      tags.insert(db.tag_names[static_cast<size_t>(range.tag)]);
    }
  }
  return tags;
}

TEST(DatabaseLoader, LoadsTheBundledFolderAt30Fps) {
  auto db = load_database({test::data_path("cmu/16")}, cmu_settings());
  ASSERT_TRUE(db) << db.error().to_string();
  EXPECT_EQ(db->fps, 30.0);
  ASSERT_EQ(db->skeletons.size(), 1u);
  EXPECT_EQ(fs::path(db->skeleton_names[0]).filename(), "16.asf");
  ASSERT_EQ(db->clips.size(), kSubject16.size());
  int next = 0;
  for (size_t i = 0; i < kSubject16.size(); ++i) {
    const DatabaseClip& clip = db->clips[i];
    EXPECT_EQ(clip.name, kSubject16[i]);  // sorted by name
    EXPECT_EQ(fs::path(clip.source).filename(), kSubject16[i] + ".amc");
    EXPECT_EQ(clip.skeleton, 0);
    const int source_frames = test::load_data_clip("cmu/16/" + kSubject16[i] + ".amc").motion.frame_count;
    EXPECT_EQ(clip.frame_count, (source_frames - 1) / 4 + 1) << clip.name;
    EXPECT_EQ(clip.motion.frame_count, clip.frame_count);
    EXPECT_EQ(clip.motion.fps, 30.0);
    EXPECT_EQ(clip.first_frame, next) << clip.name;  // back to back
    next += clip.frame_count;
  }
  EXPECT_EQ(db->frame_count(), next);
  EXPECT_EQ(db->clip_of(db->clips[3].first_frame), 3);

  const auto tags_named = [&](const std::string& name) {
    auto it = std::find(kSubject16.begin(), kSubject16.end(), name);
    return tags_of(*db, static_cast<int>(it - kSubject16.begin()));
  };
  using Set = std::set<std::string>;
  EXPECT_EQ(tags_named("16_01"), Set{"jump"});
  EXPECT_EQ(tags_named("16_05"), Set{"jump"});
  EXPECT_EQ(tags_named("16_15"), Set{"walk"});
  EXPECT_EQ(tags_named("16_17"), (Set{"walk", "turn"}));
  EXPECT_EQ(tags_named("16_33"), Set{});  // "walk, stop": walk where it walks, stop where it stops
  EXPECT_EQ(tags_named("16_35"), Set{"run"});
  EXPECT_EQ(tags_named("16_37"), Set{"run"});  // veer is no turn
  EXPECT_EQ(tags_named("16_57"), Set{});  // "run/jog, sudden stop"
  // Every frame has a tag, and the walk/run/jump frames are those of the right clips but for
  // the stops of 16_33 and 16_57, where the root stands: their last frames.
  const std::vector<TagMask> frame_tags = db->frame_tags();
  const auto bit = [&](const char* tag) {
    auto it = std::find(db->tag_names.begin(), db->tag_names.end(), tag);
    EXPECT_NE(it, db->tag_names.end()) << tag;
    return TagMask{1} << (it - db->tag_names.begin());
  };
  const TagMask locomotion = bit("walk") | bit("run") | bit("jump");
  std::vector<int> standing;
  for (size_t f = 0; f < frame_tags.size(); ++f) {
    ASSERT_NE(frame_tags[f], 0u) << f;
    if ((frame_tags[f] & locomotion) == 0) standing.push_back(static_cast<int>(f));
  }
  ASSERT_FALSE(standing.empty());
  for (const char* name : {"16_33", "16_57"}) {
    const DatabaseClip& clip = db->clips[static_cast<size_t>(std::find(kSubject16.begin(), kSubject16.end(), name) -
                                                             kSubject16.begin())];
    const int end = clip.first_frame + clip.frame_count;
    const auto in_clip = std::count_if(standing.begin(), standing.end(),
                                       [&](int f) { return f >= clip.first_frame && f < end; });
    EXPECT_GT(in_clip, 0) << name;
    EXPECT_LT(in_clip, clip.frame_count / 2) << name;
    // A run of frames up to the clip's end.
    EXPECT_EQ((frame_tags[static_cast<size_t>(end - 1)] & locomotion), 0u) << name;
    EXPECT_EQ((frame_tags[static_cast<size_t>(end - in_clip - 1)] & locomotion) != 0, true) << name;
    // Stop: on those frames and the second (30 frames) of walking or running into them, not on
    // the walk or run before (the controller asked to stop played 16_33's walk).
    int stop_frames = 0, leading = 0;
    for (int f = clip.first_frame; f < end; ++f) {
      const bool stop = (frame_tags[static_cast<size_t>(f)] & bit("stop")) != 0;
      stop_frames += stop ? 1 : 0;
      if ((frame_tags[static_cast<size_t>(f)] & locomotion) == 0) {
        EXPECT_TRUE(stop) << name << " frame " << f - clip.first_frame;
      } else if (stop) {
        ++leading;
        EXPECT_GE(f, end - in_clip - 30) << name << " frame " << f - clip.first_frame;
      }
    }
    EXPECT_EQ(leading, std::min(30, clip.frame_count - static_cast<int>(in_clip))) << name;
    EXPECT_LT(stop_frames, clip.frame_count) << name;  // the walk or run before it is none
  }
  EXPECT_EQ(db->tag_names.size(), 5u);  // walk, run, jump, turn, stop
}

TEST(DatabaseLoader, StopsWhenAsked) {
  DatabaseSettings settings = cmu_settings();
  std::stop_source stop;
  stop.request_stop();
  settings.stop = stop.get_token();
  auto db = load_database({test::data_path("cmu/16")}, settings);
  ASSERT_FALSE(db);
  EXPECT_EQ(db.error().kind, ErrorKind::kStopped);
}

// A library of a studio's own files, named for what they hold: each clip not in CMU's index is
// tagged by the words of its name, walk only where its root travels; a name without such words
// is tagged by its folder's (below the one given), and a take with neither is left untagged;
// CMU's description wins over a manifest's name for a clip it lists, and a manifest's name over
// its file's. The notes say which clips were tagged so, and by what words; name_tags off, none is.
TEST(DatabaseLoader, ClipsAreTaggedByTheWordsOfTheirNames) {
  const auto bvh = [](const Clip& clip) { return write_bvh(clip.skeleton, clip.motion, BvhWriteSettings{}); };
  const Clip walk = test::load_data_clip("cmu/16/16_15.amc");
  TempFolder folder("name-tags");
  folder.write("Walk_Forward_01.bvh", bvh(walk));
  folder.write("locomotion/RunStop.bvh", bvh(test::held_pose(walk, 0, 60)));
  folder.write("take_07.bvh", bvh(test::load_data_clip("cmu/16/16_16.amc")));
  folder.write("16_15.bvh", bvh(test::load_data_clip("cmu/16/16_11.amc")));
  folder.write("walking/w01.bvh", bvh(test::load_data_clip("cmu/16/16_13.amc")));
  DatabaseSettings settings;
  settings.cmu_index_text = "16_15\tjump\n";
  settings.mirror = DatabaseSettings::Mirroring::kOff;  // its walks turn one way: as read
  DatabaseLoadNotes notes;
  auto db = load_database({folder.path().string()}, settings, &notes);
  ASSERT_TRUE(db) << db.error().to_string();
  std::map<std::string, std::set<std::string>> tags;
  for (int c = 0; c < static_cast<int>(db->clips.size()); ++c) tags[db->clips[c].name] = tags_of(*db, c);
  ASSERT_EQ(tags.size(), 5u) << fmt::format("{}", fmt::join(load_warnings(notes), "\n"));
  EXPECT_EQ(tags.at("Walk_Forward_01"), std::set<std::string>{"walk"});
  EXPECT_EQ(tags.at("16_15"), std::set<std::string>{"jump"});  // the index's description
  EXPECT_TRUE(tags.at("take_07").empty());
  EXPECT_EQ(tags.at("w01"), std::set<std::string>{"walk"});
  // The pose held still never runs; it stops throughout.
  EXPECT_EQ(tags.at("RunStop"), std::set<std::string>{"stop"});
  ASSERT_EQ(notes.name_tagged.size(), 3u);
  std::map<std::string, DatabaseLoadNotes::NameTagged> named;
  for (const auto& n : notes.name_tagged) named[n.clip] = n;
  EXPECT_EQ(named.at("Walk_Forward_01").tags, std::vector<std::string>{"walk"});
  EXPECT_EQ(named.at("Walk_Forward_01").source, "name");
  EXPECT_EQ(named.at("RunStop").tags, (std::vector<std::string>{"run", "stop"}));
  EXPECT_EQ(named.at("w01").tags, std::vector<std::string>{"walk"});
  EXPECT_EQ(named.at("w01").source, "folder");
  EXPECT_EQ(named.at("w01").words, "walking");
  const std::vector<std::string> warnings = load_warnings(notes);
  EXPECT_TRUE(std::any_of(warnings.begin(), warnings.end(), [](const std::string& w) {
    return w.find("the library has no run") != std::string::npos && w.find("its name") != std::string::npos;
  })) << fmt::format("{}", fmt::join(warnings, "\n"));

  // A manifest's name tags a clip, unless it gives tags (none, here) or CMU's index lists the file;
  // where it says nothing, the file's name does.
  const std::string manifest = folder.write(
      "db.toml", "[[clip]]\nfile = \"take_07.bvh\"\nname = \"slow_walk\"\n[[clip]]\nfile = \"take_07.bvh\"\n"
                 "name = \"walk_given_none\"\ntags = []\n[[clip]]\nfile = \"16_15.bvh\"\nname = \"run\"\n"
                 "[[clip]]\nfile = \"Walk_Forward_01.bvh\"\nname = \"Run_Fast\"\n"
                 "[[clip]]\nfile = \"Walk_Forward_01.bvh\"\nname = \"hero\"\n");
  DatabaseLoadNotes renamed_notes;
  auto renamed = load_database({manifest}, settings, &renamed_notes);
  ASSERT_TRUE(renamed) << renamed.error().to_string();
  ASSERT_EQ(renamed->clips.size(), 5u);
  EXPECT_EQ(tags_of(*renamed, 0), std::set<std::string>{"walk"});
  EXPECT_TRUE(tags_of(*renamed, 1).empty());
  EXPECT_EQ(tags_of(*renamed, 2), std::set<std::string>{"jump"});
  EXPECT_EQ(tags_of(*renamed, 3), std::set<std::string>{"run"});
  EXPECT_EQ(tags_of(*renamed, 4), std::set<std::string>{"walk"});
  ASSERT_EQ(renamed_notes.name_tagged.size(), 3u);
  EXPECT_EQ(renamed_notes.name_tagged[2].source, "file");
  EXPECT_EQ(renamed_notes.name_tagged[2].words, "Walk_Forward_01");

  // A glTF clip named by its animation ("Take 001") and renamed: the file's own name tags it.
  auto glb = write_glb(walk.skeleton, walk.motion, "Take 001");
  ASSERT_TRUE(glb) << glb.error().to_string();
  folder.write("gl/Walk.glb", *glb);
  const std::string animated = folder.write(
      "gl.toml", "[[clip]]\nfile = \"gl/Walk.glb\"\nanimation = \"Take 001\"\nname = \"hero\"\n");
  DatabaseLoadNotes animated_notes;
  auto from_glb = load_database({animated}, settings, &animated_notes);
  ASSERT_TRUE(from_glb) << from_glb.error().to_string();
  EXPECT_EQ(tags_of(*from_glb, 0), std::set<std::string>{"walk"});
  ASSERT_EQ(animated_notes.name_tagged.size(), 1u);
  EXPECT_EQ(animated_notes.name_tagged[0].words, "Walk");

  settings.name_tags = false;
  DatabaseLoadNotes off_notes;
  auto off = load_database({folder.path().string()}, settings, &off_notes);
  ASSERT_TRUE(off) << off.error().to_string();
  for (int c = 0; c < static_cast<int>(off->clips.size()); ++c) {
    EXPECT_EQ(tags_of(*off, c), off->clips[c].name == "16_15" ? std::set<std::string>{"jump"} : std::set<std::string>{})
        << off->clips[c].name;
  }
  EXPECT_TRUE(off_notes.name_tagged.empty());
}

// A studio's library whose one turning walk turns left: each clip is mirrored, after them all,
// under NAME_mirrored (NAME_mirrored_2 where a clip has that name), with its tags on the same
// frames; the mirrored library turns as far right as left. Off, nothing is mirrored; always, a
// library that turns both ways is mirrored too.
TEST(DatabaseLoader, ALibraryTurningOneWayIsMirrored) {
  const auto bvh = [](const Clip& clip) { return write_bvh(clip.skeleton, clip.motion, BvhWriteSettings{}); };
  TempFolder folder("mirror");
  folder.write("Walk_Forward.bvh", bvh(test::load_data_clip("cmu/16/16_15.amc")));
  folder.write("walk_turn_left.bvh", bvh(test::load_data_clip("cmu/16/16_17.amc")));
  folder.write("Walk_Forward_mirrored.bvh", bvh(test::load_data_clip("cmu/16/16_16.amc")));
  DatabaseSettings settings;
  DatabaseLoadNotes notes;
  auto db = load_database({folder.path().string()}, settings, &notes);
  ASSERT_TRUE(db) << db.error().to_string();
  EXPECT_TRUE(notes.turning.lopsided());
  EXPECT_GT(notes.turning.left_deg, 45.0);
  EXPECT_LT(notes.turning.right_deg, notes.turning.left_deg / 3.0);
  EXPECT_TRUE(notes.mirrored_for_turning);
  ASSERT_EQ(db->clips.size(), 6u);
  std::map<std::string, int> clip_of;
  for (int c = 0; c < 6; ++c) clip_of[db->clips[c].name] = c;
  const std::vector<std::pair<std::string, std::string>> pairs = {
      {"Walk_Forward", "Walk_Forward_mirrored_2"},
      {"walk_turn_left", "walk_turn_left_mirrored"},
      {"Walk_Forward_mirrored", "Walk_Forward_mirrored_mirrored"}};
  std::vector<std::string> mirrored_names;
  const std::vector<TagMask> tags = db->frame_tags();
  for (const auto& [name, image] : pairs) {
    SCOPED_TRACE(name);
    ASSERT_TRUE(clip_of.contains(name) && clip_of.contains(image));
    const DatabaseClip& clip = db->clips[clip_of.at(name)];
    const DatabaseClip& mirrored = db->clips[clip_of.at(image)];
    EXPECT_LT(clip_of.at(name), 3);
    EXPECT_GE(clip_of.at(image), 3);
    mirrored_names.push_back(image);
    EXPECT_EQ(mirrored.source, clip.source);
    ASSERT_EQ(mirrored.frame_count, clip.frame_count);
    const Skeleton& skeleton = db->skeletons[static_cast<size_t>(clip.skeleton)];
    auto map = mirror_map(skeleton);
    ASSERT_TRUE(map) << map.error().message;
    const Motion expected = mirror_motion(skeleton, *map, clip.motion);
    EXPECT_EQ(mirrored.motion.local_rotations, expected.local_rotations);
    EXPECT_EQ(mirrored.motion.local_translations_m, expected.local_translations_m);
    for (int f = 0; f < clip.frame_count; ++f) {
      ASSERT_EQ(tags[static_cast<size_t>(mirrored.first_frame + f)], tags[static_cast<size_t>(clip.first_frame + f)])
          << "frame " << f;
    }
  }
  EXPECT_NE(tags_of(*db, clip_of.at("walk_turn_left_mirrored")).count("turn"), 0u);
  std::sort(mirrored_names.begin(), mirrored_names.end());
  std::vector<std::string> noted = notes.mirrored;
  std::sort(noted.begin(), noted.end());
  EXPECT_EQ(noted, mirrored_names);
  EXPECT_EQ(db->frame_contacts.size(), static_cast<size_t>(db->frame_count()));
  const TurningBalance after = turning_balance(*db);
  EXPECT_NEAR(after.right_deg, after.left_deg, 0.01 * after.left_deg);  // the root a little off the hips' middle
  EXPECT_FALSE(after.lopsided());

  // A tag that names a side names the other on the mirror (it turns the other way).
  const std::string sided = folder.write(
      "sided.toml", "[[clip]]\nfile = \"walk_turn_left.bvh\"\ntags = [\"walk\", \"turn_left\"]\n");
  auto sided_db = load_database({sided}, settings);
  ASSERT_TRUE(sided_db) << sided_db.error().to_string();
  ASSERT_EQ(sided_db->clips.size(), 2u);
  EXPECT_EQ(tags_of(*sided_db, 0), (std::set<std::string>{"walk", "turn_left"}));
  EXPECT_EQ(tags_of(*sided_db, 1), (std::set<std::string>{"walk", "turn_right"}));

  // A library of more motion than the automatic mirroring takes: said, not mirrored.
  settings.max_lopsided_mirror_s = 10.0;
  DatabaseLoadNotes long_notes;
  auto too_long = load_database({folder.path().string()}, settings, &long_notes);
  ASSERT_TRUE(too_long) << too_long.error().to_string();
  EXPECT_EQ(too_long->clips.size(), 3u);
  EXPECT_TRUE(long_notes.too_long_to_mirror && long_notes.turning.lopsided() && !long_notes.mirrored_for_turning);
  settings.max_lopsided_mirror_s = DatabaseSettings{}.max_lopsided_mirror_s;

  settings.mirror = DatabaseSettings::Mirroring::kOff;
  DatabaseLoadNotes off_notes;
  auto off = load_database({folder.path().string()}, settings, &off_notes);
  ASSERT_TRUE(off) << off.error().to_string();
  EXPECT_EQ(off->clips.size(), 3u);
  EXPECT_TRUE(off_notes.mirrored.empty());
  EXPECT_TRUE(off_notes.turning.lopsided());  // said, though not acted on
  EXPECT_FALSE(off_notes.too_long_to_mirror);

  // Walks that turn both ways: not by default, always when asked.
  TempFolder both("mirror-both");
  both.write("a.bvh", bvh(test::load_data_clip("cmu/16/16_15.amc")));
  both.write("b.bvh", bvh(test::load_data_clip("cmu/16/16_17.amc")));
  Clip right = test::load_data_clip("cmu/16/16_17.amc");
  auto right_map = mirror_map(right.skeleton);
  ASSERT_TRUE(right_map) << right_map.error().message;
  right.motion = mirror_motion(right.skeleton, *right_map, right.motion);
  both.write("c.bvh", bvh(right));
  DatabaseLoadNotes balanced_notes;
  auto balanced = load_database({both.path().string()}, DatabaseSettings{}, &balanced_notes);
  ASSERT_TRUE(balanced) << balanced.error().to_string();
  EXPECT_EQ(balanced->clips.size(), 3u);
  EXPECT_FALSE(balanced_notes.turning.lopsided());
  DatabaseSettings always;
  always.mirror = DatabaseSettings::Mirroring::kAlways;
  auto all = load_database({both.path().string()}, always);
  ASSERT_TRUE(all) << all.error().to_string();
  EXPECT_EQ(all->clips.size(), 6u);

  // A clip that looks wrong (a converter's clock 4x slow) is said to once, not for its mirror too.
  TempFolder slow("mirror-slow");
  slow.write("16_01.bvh", test::read_data("bvh/16_01.bvh"));
  DatabaseLoadNotes slow_notes;
  auto slowed = load_database({slow.path().string()}, always, &slow_notes);
  ASSERT_TRUE(slowed) << slowed.error().to_string();
  ASSERT_EQ(slowed->clips.size(), 2u);
  ASSERT_EQ(slow_notes.clip_doubts.size(), 1u);
  EXPECT_EQ(slow_notes.clip_doubts[0].name, "16_01");
}

// A take named for both ("walk_to_run"): a walk (16_15) and then a run (16_35), its root carried
// on from where the walk ends. Walk stays where it walks and run where it runs, by the pace.
TEST(DatabaseLoader, AClipNamedWalkAndRunWalksWhereItWalksAndRunsWhereItRuns) {
  const Clip walk = test::load_data_clip("cmu/16/16_15.amc");
  const Clip run = test::load_data_clip("cmu/16/16_35.amc");
  const int a = walk.motion.frame_count, b = run.motion.frame_count;
  Motion glued(walk.skeleton, a + b, walk.motion.fps);
  const int slot = walk.skeleton.translation_slot(0);
  Vec3 carry = walk.motion.translations(a - 1)[slot] - run.motion.translations(0)[slot];
  carry.y() = 0.0;
  for (int f = 0; f < a + b; ++f) {
    const Motion& from = f < a ? walk.motion : run.motion;
    const int g = f < a ? f : f - a;
    std::copy(from.rotations(g).begin(), from.rotations(g).end(), glued.rotations(f).begin());
    std::copy(from.translations(g).begin(), from.translations(g).end(), glued.translations(f).begin());
    if (f >= a) glued.translations(f)[slot] += carry;
  }
  TempFolder folder("walk-to-run");
  folder.write("walk_to_run.bvh", write_bvh(walk.skeleton, glued, BvhWriteSettings{}));
  DatabaseSettings settings;
  settings.mirror = DatabaseSettings::Mirroring::kOff;
  settings.keep_rest_frames = true;  // whole, though the seam jumps as a capture glitch would
  DatabaseLoadNotes notes;
  auto db = load_database({folder.path().string()}, settings, &notes);
  ASSERT_TRUE(db) << db.error().to_string();
  ASSERT_EQ(db->clips.size(), 1u);
  const std::vector<TagMask> tags = db->frame_tags();
  const auto tag_of = [&](const char* name) {
    return static_cast<int>(std::find(db->tag_names.begin(), db->tag_names.end(), name) - db->tag_names.begin());
  };
  const int walk_tag = tag_of("walk"), run_tag = tag_of("run");
  ASSERT_LT(walk_tag, static_cast<int>(db->tag_names.size()));
  ASSERT_LT(run_tag, static_cast<int>(db->tag_names.size()));
  // At the database's 30 fps: the walk's frames, then the run's.
  const int walked = static_cast<int>(std::lround(a * db->fps / walk.motion.fps));
  int walk_in_walk = 0, run_in_walk = 0, walk_in_run = 0, run_in_run = 0;
  for (int f = 0; f < db->frame_count(); ++f) {
    const bool w = (tags[static_cast<size_t>(f)] >> walk_tag) & 1, r = (tags[static_cast<size_t>(f)] >> run_tag) & 1;
    EXPECT_FALSE(w && r) << "frame " << f;
    (f < walked ? walk_in_walk : walk_in_run) += w;
    (f < walked ? run_in_walk : run_in_run) += r;
  }
  const int running = db->frame_count() - walked;
  EXPECT_GT(walk_in_walk, 0.8 * walked);
  EXPECT_LT(run_in_walk, 0.2 * walked);
  EXPECT_GT(run_in_run, 0.8 * running);
  EXPECT_LT(walk_in_run, 0.2 * running);
  // The travelling frames are not said to stand.
  EXPECT_TRUE(notes.standing_tags.empty() ||
              std::all_of(notes.standing_tags.begin(), notes.standing_tags.end(),
                          [](const auto& t) { return t.frames - t.tagged_frames < 10; }));

  // Read by default, the seam's jump cuts the take in two, as a capture glitch: the part that
  // walks is a walk, the one that runs a run.
  settings.keep_rest_frames = false;
  auto cut = load_database({folder.path().string()}, settings);
  ASSERT_TRUE(cut) << cut.error().to_string();
  ASSERT_EQ(cut->clips.size(), 2u);
  EXPECT_EQ(tags_of(*cut, 0), std::set<std::string>{"walk"});
  EXPECT_EQ(tags_of(*cut, 1), std::set<std::string>{"run"});
}

TEST(DatabaseLoader, CmuTagsOffOrFromText) {
  DatabaseSettings off = cmu_settings();
  off.cmu_tags = false;
  auto untagged = load_database({test::data_path("cmu/16/16_15.amc")}, off);
  ASSERT_TRUE(untagged) << untagged.error().to_string();
  EXPECT_TRUE(untagged->tag_ranges.empty());

  DatabaseSettings text;
  text.cmu_index_text = "16_15\tslow walk, stop\n";
  auto tagged = load_database({test::data_path("cmu/16/16_15.amc")}, text);
  ASSERT_TRUE(tagged) << tagged.error().to_string();
  EXPECT_EQ(tags_of(*tagged, 0), (std::set<std::string>{"walk", "stop"}));
}

// 16_15 (a walk) held still from its `freeze`th file frame on (that frame's pose repeated): the
// figure walks, then stands.
std::string walk_then_stand(int freeze) {
  const std::string amc = test::read_data("cmu/16/16_15.amc");
  std::string out, held;
  int frame = 0;
  size_t start = 0;
  while (start < amc.size()) {
    size_t end = amc.find('\n', start);
    if (end == std::string::npos) end = amc.size();
    const std::string line = amc.substr(start, end - start);
    start = end + 1;
    const bool number = !line.empty() && std::isdigit(static_cast<unsigned char>(line[0])) != 0;
    if (number) frame = std::stoi(line);
    if (frame == freeze && !number) held += line + "\n";
    out += frame > freeze && !number ? "" : line + "\n";
    if (frame > freeze && number) out += held;
  }
  return out;
}

// A description's walk stays where the root travels: the clip that stops walking loses it from
// about where its root stands (within half the second it is judged over), and the note says so;
// the unchanged walk keeps it whole, and so does every clip tagged by a manifest or with the
// travel rule off. The description's other tags (stop) are on the whole clip.
TEST(DatabaseLoader, ADescriptionsWalkStaysWhereTheRootTravels) {
  TempFolder folder("travel-tags");
  folder.write("16.asf", test::read_data("cmu/16/16.asf"));
  const int freeze = 300;  // of 471 file frames at 120 fps: frame 75 at 30 fps
  folder.write("01_01.amc", walk_then_stand(freeze));
  folder.write("01_02.amc", test::read_data("cmu/16/16_15.amc"));
  folder.write("01_03.amc", walk_then_stand(1));  // stands throughout: its "jog" is on the spot
  DatabaseSettings settings;
  settings.cmu_index_text = "01_01\twalk, stop\n01_02\twalk\n01_03\tjog, turn\n";
  DatabaseLoadNotes notes;
  auto db = load_database({folder.path().string()}, settings, &notes);
  ASSERT_TRUE(db) << db.error().to_string();
  ASSERT_EQ(db->clips.size(), 3u);
  // No frame keeps the run: the library has none, and a warning says so.
  EXPECT_EQ(tags_of(*db, 2), std::set<std::string>{"turn"});
  EXPECT_EQ(std::count(db->tag_names.begin(), db->tag_names.end(), "run"), 0);
  ASSERT_EQ(notes.vanished_tags.size(), 1u);
  EXPECT_EQ(notes.vanished_tags[0].tag, "run");
  EXPECT_EQ(notes.vanished_tags[0].clips, std::vector<std::string>{"01_03"});
  const std::vector<std::string> warnings = load_warnings(notes);
  EXPECT_TRUE(std::any_of(warnings.begin(), warnings.end(), [](const std::string& w) {
    return w.find("the library has no run") != std::string::npos && w.find("--whole-clip-tags") != std::string::npos;
  })) << fmt::format("{}", fmt::join(warnings, "\n"));
  EXPECT_TRUE(tags_of(*db, 0).empty());  // walk where it walks, stop where it stands
  EXPECT_EQ(tags_of(*db, 1), std::set<std::string>{"walk"});
  const auto walk = std::find(db->tag_names.begin(), db->tag_names.end(), "walk") - db->tag_names.begin();
  std::vector<TagRange> walks;
  for (const TagRange& r : db->tag_ranges) {
    if (r.tag == walk && r.first_frame < db->clips[1].first_frame) walks.push_back(r);
  }
  ASSERT_EQ(walks.size(), 1u);
  const int stands = freeze / 4;  // 30 of 120 fps
  EXPECT_EQ(walks[0].first_frame, 0);
  EXPECT_GE(walks[0].frame_count, stands - 15);
  EXPECT_LE(walks[0].frame_count, stands + 15);
  ASSERT_EQ(notes.standing_tags.size(), 2u);  // and 01_03's run
  EXPECT_EQ(notes.standing_tags[1].clip, "01_03");
  EXPECT_EQ(notes.standing_tags[1].tagged_frames, 0);
  EXPECT_EQ(notes.standing_tags[0].clip, "01_01");
  EXPECT_EQ(notes.standing_tags[0].tag, "walk");
  EXPECT_EQ(notes.standing_tags[0].tagged_frames, walks[0].frame_count);
  EXPECT_EQ(notes.standing_tags[0].frames, db->clips[0].frame_count);
  // Its stop: the second of walking into the stand, and the stand to the clip's end.
  const auto stop = std::find(db->tag_names.begin(), db->tag_names.end(), "stop") - db->tag_names.begin();
  std::vector<TagRange> stops;
  for (const TagRange& r : db->tag_ranges) {
    if (r.tag == stop && r.first_frame < db->clips[1].first_frame) stops.push_back(r);
  }
  ASSERT_EQ(stops.size(), 1u);
  EXPECT_EQ(stops[0].first_frame, walks[0].frame_count - 30);
  EXPECT_EQ(stops[0].first_frame + stops[0].frame_count, db->clips[0].frame_count);

  settings.travel_tags.min_speed_mps = 0.0;
  auto whole = load_database({folder.path().string()}, settings, &notes);
  ASSERT_TRUE(whole) << whole.error().to_string();
  EXPECT_EQ(tags_of(*whole, 0), (std::set<std::string>{"walk", "stop"}));
  EXPECT_EQ(tags_of(*whole, 2), (std::set<std::string>{"run", "turn"}));
  EXPECT_TRUE(notes.standing_tags.empty());
  EXPECT_TRUE(notes.vanished_tags.empty());

  const std::string manifest = folder.write(
      "db.toml", "skeleton = \"16.asf\"\n[[clip]]\nfile = \"01_01.amc\"\ntags = [\"walk\"]\n");
  auto given = load_database({manifest}, DatabaseSettings{}, &notes);
  ASSERT_TRUE(given) << given.error().to_string();
  EXPECT_EQ(tags_of(*given, 0), std::set<std::string>{"walk"});
  EXPECT_TRUE(notes.standing_tags.empty());

  settings.travel_tags.min_speed_mps = -1.0;
  auto refused = load_database({folder.path().string()}, settings);
  ASSERT_FALSE(refused);
  EXPECT_NE(refused.error().message.find("walk and run"), std::string::npos) << refused.error().message;
}

// A folder's copy of a clip in other bytes (CRLF endings) is left out with a note, as a copy of
// the same bytes is; a clip one value apart is another clip, and a file given itself is read.
// A figure that two units make a person's size (a child of 0.95 m written in centimetres is a
// giant of 2.4 m in inches): read in the closer to a typical height, with a warning naming the
// other and its --scale.
TEST(DatabaseLoader, AUnitThatWasAGuessIsWarnedOf) {
  TempFolder folder("child");
  Clip clip = test::load_data_clip("bvh/16_01.bvh");
  const double size_m = figure_size(clip.skeleton, clip.motion);
  scale_lengths(clip, 0.95 / size_m);
  BvhWriteSettings centimetres;
  centimetres.units_per_metre = 100.0;
  const std::string file = folder.write("child.bvh", write_bvh(clip.skeleton, clip.motion, centimetres));
  DatabaseLoadNotes notes;
  auto db = load_database({file}, cmu_settings(), &notes);
  ASSERT_TRUE(db) << db.error().to_string();
  const std::vector<std::string> warnings = load_warnings(notes);
  const auto line = std::find_if(warnings.begin(), warnings.end(), [](const std::string& w) {
    return w.find("a person's size too") != std::string::npos;
  });
  ASSERT_NE(line, warnings.end()) << fmt::format("{}", fmt::join(warnings, "\n"));
  EXPECT_EQ(*line, file + ": lengths read in inch (figure 2.41 m), but in cm the figure is 0.95 m, a person's size "
                          "too: --scale 0.01 reads it so");
  // The bundled subject read as it always was: no such warning.
  DatabaseLoadNotes bundled;
  ASSERT_TRUE(load_database({test::data_path("bvh")}, cmu_settings(), &bundled));
  for (const std::string& w : load_warnings(bundled)) EXPECT_EQ(w.find("a person's size too"), std::string::npos) << w;
}

TEST(DatabaseLoader, AFoldersCopyOfAMotionInOtherBytesIsLeftOut) {
  TempFolder folder("motion-copies");
  const std::string walk = test::read_data("cmu/16/16_15.amc");
  folder.write("16.asf", test::read_data("cmu/16/16.asf"));
  folder.write("16_15.amc", walk);
  std::string crlf;
  for (char c : walk) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
  folder.write("walk_crlf.amc", crlf);
  std::string changed = walk;
  const size_t x = changed.find("\nroot ") + 6;  // the first frame's root x
  ASSERT_TRUE(std::isdigit(static_cast<unsigned char>(changed.at(x))));
  changed.insert(x, "1");  // 10 cm further (CMU's units: 1/0.45 inch) at its first frame
  folder.write("walk_moved.amc", changed);
  DatabaseLoadNotes notes;
  auto db = load_database({folder.path().string()}, cmu_settings(), &notes);
  ASSERT_TRUE(db) << db.error().to_string();
  std::vector<std::string> names;
  for (const DatabaseClip& clip : db->clips) names.push_back(clip.name);
  EXPECT_EQ(names, (std::vector<std::string>{"16_15", "walk_moved"}));
  const std::string expected = fmt::format("{} left out: the same motion as {}, in other bytes (a copy)",
                                           (folder.path() / "walk_crlf.amc").string(),
                                           (folder.path() / "16_15.amc").string());
  EXPECT_NE(std::find(notes.name_clashes.begin(), notes.name_clashes.end(), expected), notes.name_clashes.end());
}

TEST(DatabaseLoader, ClipsNamedLikeCmusGetTagsFromTheShippedIndexWhenNoneIsGiven) {
  // Copies in a folder with no index beside or above it; 16_15 is "walk" in CMU's index,
  // 16_57 "run/jog, sudden stop"; a clip under another name, which says no motion, gets no tags.
  TempFolder folder("shipped-index");
  folder.write("16.asf", test::read_data("cmu/16/16.asf"));
  folder.write("16_15.amc", test::read_data("cmu/16/16_15.amc"));
  folder.write("16_57.amc", test::read_data("cmu/16/16_57.amc"));
  folder.write("take_3.amc", test::read_data("cmu/16/16_16.amc"));
  DatabaseSettings none;
  ASSERT_TRUE(none.cmu_index_path.empty() && none.cmu_index_text.empty());
  auto db = load_database({folder.path().string()}, none);
  ASSERT_TRUE(db) << db.error().to_string();
  ASSERT_EQ(db->clips.size(), 3u);
  EXPECT_EQ(tags_of(*db, 0), std::set<std::string>{"walk"});
  EXPECT_TRUE(tags_of(*db, 1).empty());  // its run only where it runs, its stop where it stops
  EXPECT_TRUE(tags_of(*db, 2).empty());
  DatabaseSettings whole;
  whole.travel_tags.min_speed_mps = 0.0;
  auto as_said = load_database({folder.path().string()}, whole);
  ASSERT_TRUE(as_said) << as_said.error().to_string();
  EXPECT_EQ(tags_of(*as_said, 1), (std::set<std::string>{"run", "stop"}));
  // --no-cmu-tags still turns them off.
  none.cmu_tags = false;
  auto off = load_database({folder.path().string()}, none);
  ASSERT_TRUE(off) << off.error().to_string();
  EXPECT_TRUE(off->tag_ranges.empty());
}

TEST(DatabaseLoader, OtherFrameRates) {
  DatabaseSettings settings = cmu_settings();
  settings.fps = 120;
  auto db = load_database({test::data_path("cmu/16/16_15.amc")}, settings);
  ASSERT_TRUE(db) << db.error().to_string();
  EXPECT_EQ(db->clips[0].frame_count, test::load_data_clip("cmu/16/16_15.amc").motion.frame_count);
}

TEST(DatabaseLoader, ManifestWithFrameRangeAndRangeTags) {
  TempFolder folder("manifest");
  const std::string manifest = folder.write("db.toml", fmt::format(R"(fps = 30
skeleton = "{0}/16.asf"

[[clip]]
file = "{0}/16_15.amc"
name = "walk_middle"
first_frame = 41
last_frame = 240
tags = ["walk"]
ranges = [
  {{ first_frame = 41, last_frame = 120, tags = ["start"] }},
  {{ first_frame = 121, last_frame = 240, tags = ["steady"] }},
]

[[clip]]
file = "{0}/16_35.amc"
name = "jog"

[[clip]]
file = "{0}/16_57.amc"
tags = []
)", folder.relative_data("cmu/16")));
  auto db = load_database({manifest}, cmu_settings());
  ASSERT_TRUE(db) << db.error().to_string();
  ASSERT_EQ(db->clips.size(), 3u);

  // Frames 41..240 of the file (200 frames at 120 fps) -> 50 frames at 30 fps.
  const DatabaseClip& walk = db->clips[0];
  EXPECT_EQ(walk.name, "walk_middle");
  EXPECT_EQ(walk.first_frame, 0);
  EXPECT_EQ(walk.frame_count, 50);
  // Frame numbers are 1-based and the file's: the clip's first frame is file frame 41, motion
  // index 40 but for the two frames the reader dropped (16_15 opens on a capture glitch).
  const Clip source = test::load_data_clip("cmu/16/16_15.amc");
  ASSERT_EQ(source.glitched_leading_frames, 2);
  const int at = 40 - source.glitched_leading_frames;
  for (int j = 0; j < source.motion.joint_count; ++j) {
    EXPECT_LT(walk.motion.rotations(0)[j].angularDistance(source.motion.rotations(at)[j]), 1e-9) << j;
    EXPECT_LT(walk.motion.rotations(49)[j].angularDistance(source.motion.rotations(at + 196)[j]), 1e-9) << j;
  }
  EXPECT_LT((walk.motion.translations(0)[0] - source.motion.translations(at)[0]).norm(), 1e-12);

  // The range tags split the clip where file frame 121 falls: [0, 19] and [20, 49].
  const auto range_of = [&](const char* tag) {
    auto it = std::find(db->tag_names.begin(), db->tag_names.end(), tag);
    EXPECT_NE(it, db->tag_names.end()) << tag;
    std::vector<std::pair<int, int>> ranges;
    for (const TagRange& r : db->tag_ranges) {
      if (r.tag == it - db->tag_names.begin()) ranges.emplace_back(r.first_frame, r.frame_count);
    }
    return ranges;
  };
  EXPECT_EQ(range_of("walk"), (std::vector<std::pair<int, int>>{{0, 50}}));
  EXPECT_EQ(range_of("start"), (std::vector<std::pair<int, int>>{{0, 20}}));
  EXPECT_EQ(range_of("steady"), (std::vector<std::pair<int, int>>{{20, 30}}));

  // A clip the manifest gives no tags takes them from the CMU index (by its file's name, also
  // when renamed); `tags = []` means none.
  EXPECT_EQ(db->clips[1].name, "jog");
  EXPECT_EQ(db->clips[1].first_frame, 50);
  EXPECT_EQ(tags_of(*db, 1), std::set<std::string>{"run"});
  EXPECT_TRUE(tags_of(*db, 2).empty());
  EXPECT_EQ(db->clips[2].first_frame, db->clips[1].first_frame + db->clips[1].frame_count);
  EXPECT_EQ(db->skeletons.size(), 1u);
}

TEST(DatabaseLoader, ManifestFpsWinsUnlessTheCallerSaysOtherwise) {
  TempFolder folder("fps");
  const std::string manifest = folder.write(
      "db.toml", fmt::format("fps = 60\n[[clip]]\nfile = \"{}\"\n", folder.relative_data("cmu/16/16_15.amc")));
  auto db = load_database({manifest}, cmu_settings());
  ASSERT_TRUE(db) << db.error().to_string();
  EXPECT_EQ(db->fps, 60.0);
  EXPECT_EQ(db->clips[0].motion.fps, 60.0);

  DatabaseSettings given = cmu_settings();
  given.prefer_manifest_fps = false;
  given.fps = 40;
  auto forced = load_database({manifest}, given);
  ASSERT_TRUE(forced) << forced.error().to_string();
  EXPECT_EQ(forced->fps, 40.0);

  const std::string other = folder.write(
      "other.toml", fmt::format("\nfps = 30\n[[clip]]\nfile = \"{}\"\n", folder.relative_data("cmu/16/16_35.amc")));
  auto clash = load_database({manifest, other}, cmu_settings());
  ASSERT_FALSE(clash);
  EXPECT_EQ(clash.error().file, other);
  EXPECT_EQ(clash.error().line, 2);
  EXPECT_NE(clash.error().message.find("differs"), std::string::npos) << clash.error().to_string();
}

TEST(DatabaseLoader, SkeletonFilesWithTheSameJointsShareADatabase) {
  TempFolder folder("copy");
  folder.write("16.asf", test::read_data("cmu/16/16.asf"));
  // A clip of its own (the same motion would be read once): its first root x further.
  std::string walk = test::read_data("cmu/16/16_15.amc");
  const size_t x = walk.find("\nroot ") + 6;
  ASSERT_TRUE(std::isdigit(static_cast<unsigned char>(walk.at(x))));
  folder.write("16_15.amc", walk.insert(x, "1"));
  auto db = load_database({test::data_path("cmu/16"), folder.path().string()}, cmu_settings());
  ASSERT_TRUE(db) << db.error().to_string();
  ASSERT_EQ(db->skeletons.size(), 2u);
  ASSERT_EQ(db->clips.size(), 16u);
  EXPECT_EQ(db->clips[14].skeleton, 0);
  EXPECT_EQ(db->clips[15].skeleton, 1);
  EXPECT_EQ(db->skeleton_names[1], (folder.path() / "16.asf").string());
}

TEST(DatabaseLoader, ClipsOfOneAsfReadWithOtherUpAxesGetTheirOwnSkeletons) {
  // The same AMC twice, once told z up: that one is turned ((x, y, z) to (x, z, -y)), on a skeleton
  // of its own, and every world position is the other's turned.
  TempFolder folder("up");
  const std::string manifest = folder.write(
      "db.toml", fmt::format("skeleton = \"{0}/16.asf\"\n[[clip]]\nfile = \"{0}/16_15.amc\"\n[[clip]]\nfile = "
                             "\"{0}/16_15.amc\"\nname = \"turned\"\nup_axis = \"z\"\n",
                             folder.relative_data("cmu/16")));
  DatabaseLoadNotes notes;
  auto db = load_database({manifest}, cmu_settings(), &notes);
  ASSERT_TRUE(db) << db.error().to_string();
  ASSERT_EQ(db->clips.size(), 2u);
  ASSERT_EQ(db->skeletons.size(), 2u);
  EXPECT_EQ(db->clips[0].skeleton, 0);
  EXPECT_EQ(db->clips[1].skeleton, 1);
  ASSERT_EQ(notes.detected_up_axes.size(), 1u);  // the first clip's was chosen, and it stands
  EXPECT_EQ(notes.detected_up_axes[0].choice.axis, UpAxis::kY);
  const std::vector<Vec3> y = world_positions(db->skeletons[0], db->clips[0].motion);
  const std::vector<Vec3> z = world_positions(db->skeletons[1], db->clips[1].motion);
  ASSERT_EQ(y.size(), z.size());
  double worst = 0.0;
  for (size_t i = 0; i < y.size(); ++i) worst = std::max(worst, (Vec3(y[i].x(), y[i].z(), -y[i].y()) - z[i]).norm());
  EXPECT_LT(worst, 1e-9);
}

TEST(DatabaseLoader, AFileWhoseOwnUpAxisIsNotSettledIsReadInTheLibrarys) {
  // Three walks written z up, and a fourth of the same z-up rig whose figure lies along the
  // file's y all through (crawling): alone it reads y (its animation wins over its rest pose),
  // among the others it reads z like them, as if told. A file given its axis is not judged.
  TempFolder folder("library-up");
  const Quat to_z = up_axis_to_y(UpAxis::kZ).conjugate();
  const auto z_up_file = [&](const char* clip_file, const std::string& name, bool lying) {
    Clip clip = test::load_data_clip(clip_file);
    if (lying) {  // along y-up's z, which the turn to z up makes the file's -y
      const int slot = clip.skeleton.translation_slot(0);
      for (int f = 0; f < clip.motion.frame_count; ++f) {
        clip.motion.rotations(f)[0] = to_z * clip.motion.rotations(f)[0];
        clip.motion.translations(f)[slot] = to_z * clip.motion.translations(f)[slot];
      }
    }
    turn_clip(clip, to_z);
    return folder.write(name, write_bvh(clip.skeleton, clip.motion, BvhWriteSettings{}));
  };
  std::vector<std::string> files;
  for (const char* walk : {"cmu/16/16_15.amc", "cmu/16/16_16.amc", "cmu/16/16_11.amc"}) {
    files.push_back(z_up_file(walk, fmt::format("walk{}.bvh", files.size()), false));
  }
  const std::string crawl = z_up_file("cmu/16/16_13.amc", "crawl.bvh", true);

  DatabaseSettings settings = cmu_settings();
  DatabaseLoadNotes alone_notes;
  auto alone = load_database({crawl}, settings, &alone_notes);
  ASSERT_TRUE(alone) << alone.error().to_string();
  ASSERT_EQ(alone_notes.detected_up_axes.size(), 1u);
  EXPECT_EQ(alone_notes.detected_up_axes[0].axis_read(), UpAxis::kY);
  EXPECT_FALSE(up_axis_settled(alone_notes.detected_up_axes[0].choice));

  files.push_back(crawl);
  settings.mirror = DatabaseSettings::Mirroring::kOff;  // its walks turn one way: as read
  DatabaseLoadNotes notes;
  auto library = load_database(files, settings, &notes);
  ASSERT_TRUE(library) << library.error().to_string();
  ASSERT_EQ(library->clips.size(), 4u);
  ASSERT_EQ(notes.detected_up_axes.size(), 4u);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(notes.detected_up_axes[i].axis_read(), UpAxis::kZ) << i;
    EXPECT_FALSE(notes.detected_up_axes[i].library_axis) << i;
  }
  const auto& followed = notes.detected_up_axes[3];
  EXPECT_EQ(followed.file, crawl);
  EXPECT_EQ(followed.choice.axis, UpAxis::kY);
  EXPECT_EQ(followed.library_axis, UpAxis::kZ);

  // A file cut into several clips votes once: two walks (the first also cut again) and the crawl
  // given as two frame ranges still read the crawl z up, with one note a file.
  const std::string manifest = folder.write(
      "split.toml", fmt::format("[[clip]]\nfile = \"{}\"\n[[clip]]\nfile = \"{}\"\n[[clip]]\nfile = \"{}\"\n"
                                "name = \"crawl_a\"\nlast_frame = 150\n[[clip]]\nfile = \"{}\"\nname = \"crawl_b\"\n"
                                "first_frame = 151\n[[clip]]\nfile = \"{}\"\nname = \"walk_again\"\nlast_frame = 100\n",
                                files[0], files[1], crawl, crawl, files[0]));
  DatabaseLoadNotes split_notes;
  auto split = load_database({manifest}, settings, &split_notes);
  ASSERT_TRUE(split) << split.error().to_string();
  ASSERT_EQ(split->clips.size(), 5u);
  int followed_notes = 0;
  for (const auto& d : split_notes.detected_up_axes) followed_notes += d.library_axis ? 1 : 0;
  EXPECT_EQ(followed_notes, 1);
  EXPECT_EQ(split_notes.detected_up_axes.size(), 3u);  // a note a file: two walks (one cut twice), the crawl
  // Its first clip starts where the whole file does, read z up as in the library.
  EXPECT_EQ(world_positions(split->skeletons[split->clips[2].skeleton], split->clips[2].motion).front(),
            world_positions(library->skeletons[library->clips[3].skeleton], library->clips[3].motion).front());

  // With fingers in one walk as well: kept on the shared joints and the crawl z up, both noted;
  // the crawl moves as in the library without fingers.
  Clip fingered = test::with_fingers(test::load_data_clip("cmu/16/16_16.amc"));
  turn_clip(fingered, to_z);
  std::vector<std::string> with_fingers = files;
  with_fingers[1] = folder.write("fingers.bvh", write_bvh(fingered.skeleton, fingered.motion, BvhWriteSettings{}));
  // And a walk under MotionBuilder's names: renamed as it is read, before the joints are kept.
  Clip builder = renamed_as(test::load_data_clip("cmu/16/16_11.amc"), test::load_data_clip("bvh/111_36.bvh").skeleton);
  turn_clip(builder, to_z);
  with_fingers[2] = folder.write("builder.bvh", write_bvh(builder.skeleton, builder.motion, BvhWriteSettings{}));
  DatabaseLoadNotes fingers_notes;
  auto both = load_database(with_fingers, settings, &fingers_notes);
  ASSERT_TRUE(both) << both.error().to_string();
  EXPECT_EQ(fingers_notes.common_joints.size(), static_cast<size_t>(library->skeletons[0].joint_count()));
  ASSERT_EQ(fingers_notes.dropped_joints.size(), 1u);
  EXPECT_EQ(fingers_notes.dropped_joints[0].skeleton, with_fingers[1]);
  ASSERT_EQ(fingers_notes.detected_up_axes.size(), 4u);
  EXPECT_EQ(fingers_notes.detected_up_axes[3].library_axis, UpAxis::kZ);
  const std::vector<std::string> fingers_warnings = load_warnings(fingers_notes);
  ASSERT_EQ(fingers_warnings.size(), 4u);  // the crawl followed, the fingers dropped, the names, the crawl's floor
  EXPECT_NE(fingers_warnings[0].find("crawl.bvh: read z up like the library's other files"), std::string::npos);
  EXPECT_NE(fingers_warnings[1].find("dropped lwrist_finger0"), std::string::npos);
  EXPECT_NE(fingers_warnings[2].find("builder.bvh: its joints are the library's first rig's under other names"),
            std::string::npos);
  EXPECT_NE(fingers_warnings[3].find("crawl: its lowest joint"), std::string::npos);
  EXPECT_EQ(world_positions(both->skeletons[both->clips[2].skeleton], both->clips[2].motion),
            world_positions(library->skeletons[library->clips[2].skeleton], library->clips[2].motion));
  EXPECT_EQ(world_positions(both->skeletons[both->clips[3].skeleton], both->clips[3].motion),
            world_positions(library->skeletons[library->clips[3].skeleton], library->clips[3].motion));

  settings.up_axis = UpAxis::kZ;
  DatabaseLoadNotes told_notes;
  auto told = load_database({crawl}, settings, &told_notes);
  ASSERT_TRUE(told) << told.error().to_string();
  EXPECT_TRUE(told_notes.detected_up_axes.empty());
  const DatabaseClip& in_library = library->clips[3];
  const std::vector<Vec3> got = world_positions(library->skeletons[in_library.skeleton], in_library.motion);
  const std::vector<Vec3> want = world_positions(told->skeletons[0], told->clips[0].motion);
  ASSERT_EQ(got.size(), want.size());
  for (size_t i = 0; i < got.size(); ++i) ASSERT_EQ(got[i], want[i]) << i;
  // The clips before it are what they are without it.
  auto walks = load_database({files[0], files[1], files[2]}, cmu_settings());
  ASSERT_TRUE(walks) << walks.error().to_string();
  for (int c = 0; c < 3; ++c) {
    EXPECT_EQ(world_positions(walks->skeletons[walks->clips[c].skeleton], walks->clips[c].motion),
              world_positions(library->skeletons[library->clips[c].skeleton], library->clips[c].motion))
        << c;
  }
}

TEST(DatabaseLoader, ClipsInPlaceGetTheirTravelFromTheFeetUnlessTold) {
  // A walk written in place (the hips' floor travel taken out), twice: once as it comes, once
  // told `travel = "root"`. The first travels as the capture did, the second stays on the spot.
  Clip walk = test::load_data_clip("cmu/16/16_15.amc");
  const int slot = walk.skeleton.translation_slot(0);
  for (int f = 0; f < walk.motion.frame_count; ++f) walk.motion.translations(f)[slot].x() = 0.0;
  for (int f = 0; f < walk.motion.frame_count; ++f) walk.motion.translations(f)[slot].z() = 0.0;
  TempFolder folder("inplace");
  folder.write("walk.bvh", test::static_root_bvh(walk));
  const std::string manifest =
      folder.write("db.toml", "[[clip]]\nfile = \"walk.bvh\"\n[[clip]]\nfile = \"walk.bvh\"\nname = \"as_read\"\n"
                              "travel = \"root\"\n");
  DatabaseLoadNotes notes;
  auto db = load_database({manifest}, cmu_settings(), &notes);
  ASSERT_TRUE(db) << db.error().to_string();
  ASSERT_EQ(db->clips.size(), 2u);
  ASSERT_EQ(notes.recovered_travels.size(), 1u);
  EXPECT_EQ(notes.recovered_travels[0].source, TravelSource::kAuto);
  EXPECT_TRUE(notes.recovered_travels[0].choice.in_place);
  EXPECT_GT(notes.recovered_travels[0].choice.recovered_m, 3.5);  // the capture's 3.9 m, less its feet's slip
  const auto floor_span = [&](int clip) {
    const std::vector<Vec3> world = world_positions(db->skeletons[db->clips[clip].skeleton], db->clips[clip].motion);
    const size_t joints = world.size() / db->clips[clip].motion.frame_count;
    Vec3 d = world[world.size() - joints] - world[0];
    d.y() = 0.0;
    return d.norm();
  };
  EXPECT_GT(floor_span(0), 3.5);
  EXPECT_LT(floor_span(1), 0.2);
}

TEST(DatabaseLoader, SkeletonsThatDifferInSomeJointsAreReadOnTheJointsTheyShare) {
  // Two walks as BVH, one exported with fingers: every clip is read on the joints both have,
  // each moving as its own file has it; the notes name the fingers and their file.
  TempFolder folder("fingers");
  const Clip plain = test::load_data_clip("cmu/16/16_15.amc");
  const Clip other = test::load_data_clip("cmu/16/16_16.amc");
  const std::string plain_file = folder.write("a.bvh", write_bvh(plain.skeleton, plain.motion, BvhWriteSettings{}));
  const Clip fingers = test::with_fingers(other);
  const std::string fingers_file =
      folder.write("b.bvh", write_bvh(fingers.skeleton, fingers.motion, BvhWriteSettings{}));
  const std::string other_file = folder.write("c.bvh", write_bvh(other.skeleton, other.motion, BvhWriteSettings{}));

  DatabaseLoadNotes notes;
  auto db = load_database({plain_file, fingers_file}, cmu_settings(), &notes);
  ASSERT_TRUE(db) << db.error().to_string();
  ASSERT_EQ(db->clips.size(), 2u);
  ASSERT_EQ(db->skeletons.size(), 2u);
  EXPECT_EQ(db->skeletons[1].joint_count(), db->skeletons[0].joint_count());
  ASSERT_EQ(notes.dropped_joints.size(), 1u);
  EXPECT_EQ(notes.dropped_joints[0].skeleton, fingers_file);
  EXPECT_EQ(notes.dropped_joints[0].joints.size(), 8u);  // 3 a finger, and the End Site BVH gives its tip
  EXPECT_EQ(notes.common_joints.size(), static_cast<size_t>(db->skeletons[0].joint_count()));
  const std::vector<std::string> warnings = load_warnings(notes);
  ASSERT_FALSE(warnings.empty());
  EXPECT_NE(warnings[0].find("dropped lwrist_finger0"), std::string::npos) << warnings[0];
  // The fingered walk plays as the same walk without fingers, read on its own.
  auto alone = load_database({other_file}, cmu_settings());
  ASSERT_TRUE(alone) << alone.error().to_string();
  EXPECT_EQ(world_positions(db->skeletons[1], db->clips[1].motion),
            world_positions(alone->skeletons[0], alone->clips[0].motion));
  EXPECT_FALSE(db->frame_contacts.empty());  // the feet are found on the shared joints
}

TEST(DatabaseLoader, ARootMotionJointAboveTheHipsIsComposedIntoThemWhenTheOtherRigsStartThere) {
  // A game engine's export (a root-motion joint above the root) beside plain files: the library
  // is read from the plain files' root down, in either order, each clip moving as its file has it.
  TempFolder folder("reroot");
  const Clip plain = test::load_data_clip("cmu/16/16_15.amc");
  const Clip other = test::load_data_clip("cmu/16/16_16.amc");
  auto engine = add_root_motion(other.skeleton, other.motion, learn_clip_forward_axis(other.skeleton, other.motion),
                                RootMotionSettings{});
  ASSERT_TRUE(engine) << engine.error().to_string();
  const std::string plain_file = folder.write("a.bvh", write_bvh(plain.skeleton, plain.motion, BvhWriteSettings{}));
  const std::string engine_file = folder.write("b.bvh", write_bvh(engine->skeleton, engine->motion, BvhWriteSettings{}));
  const std::string other_file = folder.write("c.bvh", write_bvh(other.skeleton, other.motion, BvhWriteSettings{}));
  DatabaseSettings settings = cmu_settings();
  settings.fps = 120.0;  // the files' rate: no resampling, so the composition is exact
  auto alone = load_database({other_file}, settings);
  ASSERT_TRUE(alone) << alone.error().to_string();
  const std::vector<Vec3> want = world_positions(alone->skeletons[0], alone->clips[0].motion);
  for (const bool engine_first : {false, true}) {
    DatabaseLoadNotes notes;
    auto db = load_database(engine_first ? std::vector<std::string>{engine_file, plain_file}
                                         : std::vector<std::string>{plain_file, engine_file},
                            settings, &notes);
    ASSERT_TRUE(db) << db.error().to_string();
    ASSERT_EQ(db->clips.size(), 2u);
    for (const Skeleton& skeleton : db->skeletons) {
      EXPECT_EQ(skeleton.joint(0).name, "root");
      EXPECT_EQ(skeleton.joint_count(), alone->skeletons[0].joint_count());
    }
    ASSERT_EQ(notes.rerooted.size(), 1u);
    EXPECT_EQ(notes.rerooted[0].skeleton, engine_file);
    EXPECT_EQ(notes.rerooted[0].root, "root");
    EXPECT_EQ(notes.rerooted[0].above, std::vector<std::string>{"root_motion"});
    EXPECT_TRUE(notes.rerooted[0].dropped.empty());
    const DatabaseClip& clip = db->clips[engine_first ? 0 : 1];
    const std::vector<Vec3> got = world_positions(db->skeletons[static_cast<size_t>(clip.skeleton)], clip.motion);
    ASSERT_EQ(got.size(), want.size());
    double worst = 0.0;
    for (size_t i = 0; i < want.size(); ++i) worst = std::max(worst, (got[i] - want[i]).norm());
    EXPECT_LT(worst, 1e-4) << engine_first;  // the BVH text's rounding
    const std::vector<std::string> warnings = load_warnings(notes);
    EXPECT_TRUE(std::any_of(warnings.begin(), warnings.end(), [&](const std::string& line) {
      return line.find("b.bvh: read from 'root' down, the root of the library's other rigs: the motion of "
                       "'root_motion' above it is composed into it") != std::string::npos;
    })) << fmt::format("{}", fmt::join(warnings, "\n"));
    EXPECT_FALSE(db->frame_contacts.empty());  // the feet are found
  }
}

TEST(DatabaseLoader, AHeldPoseOfARigWhoseRootTravelsWithoutTurningJoinsItsWalks) {
  // An engine's library: the walk's root carries the translation alone (folded at import, its
  // root kept to write back, the IK helper dropped); a pose held still does not travel, so
  // it is not folded there. The library reads it from the walk's body joint down, its root
  // kept to write back as the walk's is, every joint where its file has it.
  TempFolder folder("held");
  const Clip walk = test::load_data_clip("cmu/16/16_15.amc");
  const Clip pose = test::held_pose(walk, 40, 60);
  const Clip engine_walk = test::translation_root_clip(walk, Quat::Identity(), 0.0, true);
  const Clip engine_pose = test::translation_root_clip(pose, Quat::Identity(), 0.0, true);
  const std::string walk_file =
      folder.write("a.bvh", write_bvh(engine_walk.skeleton, engine_walk.motion, BvhWriteSettings{}));
  const std::string pose_file =
      folder.write("b.bvh", write_bvh(engine_pose.skeleton, engine_pose.motion, BvhWriteSettings{}));
  DatabaseSettings settings = cmu_settings();
  settings.fps = 120.0;
  for (const bool pose_first : {false, true}) {
    DatabaseLoadNotes notes;
    auto db = load_database(pose_first ? std::vector<std::string>{pose_file, walk_file}
                                       : std::vector<std::string>{walk_file, pose_file},
                            settings, &notes);
    ASSERT_TRUE(db) << db.error().to_string();
    ASSERT_EQ(db->skeletons.size(), 2u);
    for (const Skeleton& skeleton : db->skeletons) {
      EXPECT_EQ(skeleton.joint(0).name, "root");
      ASSERT_EQ(skeleton.static_ancestors().size(), 1u);
      EXPECT_EQ(skeleton.static_ancestors()[0].name, "root_motion");
      EXPECT_FALSE(skeleton.find("ik_foot_l"));
    }
    ASSERT_EQ(notes.folded_roots.size(), 1u);
    EXPECT_EQ(notes.folded_roots[0].skeleton, walk_file);
    EXPECT_EQ(notes.folded_roots[0].dropped, std::vector<std::string>{"ik_foot_l"});
    ASSERT_EQ(notes.rerooted.size(), 1u);
    EXPECT_EQ(notes.rerooted[0].skeleton, pose_file);
    EXPECT_EQ(notes.rerooted[0].dropped, std::vector<std::string>{"ik_foot_l"});
    const DatabaseClip& held = db->clips[pose_first ? 0 : 1];
    Clip read;
    read.name = held.name;
    read.skeleton = db->skeletons[static_cast<size_t>(held.skeleton)];
    read.motion = held.motion;
    EXPECT_LT(test::max_apart(read, pose), 1e-4);  // the BVH text's rounding
  }
}

TEST(DatabaseLoader, OneRigUnderOtherNamesInGltfAndBvhIsMatched) {
  // The same rig written to glTF (its end sites nodes among the joints) and, under a prefix
  // an exporter adds, to BVH (its End Sites last): one hierarchy, matched joint by joint.
  TempFolder folder("formats");
  const Clip walk = test::load_data_clip("cmu/16/16_15.amc");
  const Clip other = test::load_data_clip("cmu/16/16_16.amc");
  auto glb = write_glb(walk.skeleton, walk.motion, "walk");
  ASSERT_TRUE(glb) << glb.error().to_string();
  const std::string glb_file = folder.write("a.glb", *glb);
  std::vector<JointDef> prefixed(other.skeleton.joints().begin(), other.skeleton.joints().end());
  for (JointDef& joint : prefixed) joint.name = "mixamorig:" + joint.name;
  const std::string bvh_file =
      folder.write("b.bvh", write_bvh(Skeleton(prefixed), other.motion, BvhWriteSettings{}));
  DatabaseLoadNotes notes;
  auto db = load_database({glb_file, bvh_file}, cmu_settings(), &notes);
  ASSERT_TRUE(db) << db.error().to_string();
  ASSERT_EQ(notes.matched_rigs.size(), 1u);
  EXPECT_EQ(notes.matched_rigs[0].file, bvh_file);
  EXPECT_EQ(db->skeletons[1].joint(0).name, "root");  // the first's names
}

TEST(DatabaseLoader, AClipIsCutAtCaptureGlitchesWithinIt) {
  // 16_16 with its right upper arm turned by 100 degrees for frames 201..210 of the file (a
  // twelfth of a second at 120 fps): read as two clips, the frames between the glitches
  // dropped; a manifest's ranges cover what each part keeps of them, and one wholly in the
  // dropped frames is an error at its line. CMU's description tags both parts.
  TempFolder folder("within");
  const Clip clean = test::load_whole_data_clip("cmu/16/16_16.amc");
  const int n = clean.motion.frame_count;
  const Clip glitched = test::with_turn(clean, "rhumerus", 200, 209, 1.745);
  const std::string file = folder.write("16_16.bvh", write_bvh(glitched.skeleton, glitched.motion, BvhWriteSettings{}));
  const std::string other =
      folder.write("16_16_part2.bvh", write_bvh(clean.skeleton, clean.motion.slice(0, 100), BvhWriteSettings{}));
  DatabaseSettings settings = cmu_settings();
  settings.fps = 120.0;  // the file's rate: frames are frames
  DatabaseLoadNotes notes;
  auto db = load_database({file, other}, settings, &notes);
  ASSERT_TRUE(db) << db.error().to_string();
  ASSERT_EQ(db->clips.size(), 3u);
  // The second part's name is taken by the other file's clip: it gets one of its own, with a
  // warning.
  EXPECT_NE(std::find(notes.name_clashes.begin(), notes.name_clashes.end(),
                      file + ": a clip is named 16_16_part2 already; this clip's part 2, cut at capture glitches, is "
                             "16_16_part2_2"),
            notes.name_clashes.end())
      << fmt::format("{}", fmt::join(notes.name_clashes, "\n"));
  EXPECT_EQ(db->clips[0].name, "16_16");
  EXPECT_EQ(db->clips[1].name, "16_16_part2_2");
  EXPECT_EQ(db->clips[2].name, "16_16_part2");
  EXPECT_EQ(db->clips[0].frame_count, 200);
  EXPECT_EQ(db->clips[1].frame_count, n - 210);
  EXPECT_EQ(db->clips[1].first_frame, 200);
  EXPECT_EQ(db->clips[1].source, file);
  for (int j = 0; j < clean.motion.joint_count; ++j) {  // the part is the file from frame 211 on
    EXPECT_TRUE(db->clips[1].motion.rotations(0)[j].isApprox(clean.motion.rotations(210)[j], 1e-6)) << j;
  }
  ASSERT_EQ(notes.glitch_splits.size(), 1u);
  const DatabaseLoadNotes::GlitchSplit& split = notes.glitch_splits[0];
  EXPECT_EQ(split.file, file);
  EXPECT_EQ(split.clip, "16_16");
  ASSERT_EQ(split.glitches.size(), 2u);
  EXPECT_EQ(split.glitches[0].frame, 200);  // from the file's frame 200 to 201
  EXPECT_DOUBLE_EQ(split.glitches[0].seconds, 200.0 / 120.0);
  EXPECT_EQ(split.glitches[1].frame, 210);
  EXPECT_EQ(split.glitches[0].joint.front(), 'r') << split.glitches[0].joint;
  ASSERT_EQ(split.parts.size(), 2u);
  EXPECT_EQ(split.parts[0].clip, "16_16");
  EXPECT_EQ(split.parts[0].first_frame, 1);
  EXPECT_EQ(split.parts[0].last_frame, 200);
  EXPECT_EQ(split.parts[1].clip, "16_16_part2_2");
  EXPECT_EQ(split.parts[1].first_frame, 211);
  EXPECT_EQ(split.parts[1].last_frame, n);
  EXPECT_EQ(split.dropped_frames, 10);
  // CMU's "walk" where each part's root travels: on both.
  const int walk = db->tag_index("walk");
  ASSERT_GE(walk, 0);
  for (int c : {0, 1}) {
    const DatabaseClip& part = db->clips[static_cast<size_t>(c)];
    const bool tagged = std::any_of(db->tag_ranges.begin(), db->tag_ranges.end(), [&](const TagRange& r) {
      return r.tag == walk && r.first_frame >= part.first_frame && r.first_frame < part.first_frame + part.frame_count;
    });
    EXPECT_TRUE(tagged) << part.name;
  }

  // A manifest's ranges, in the file's frames.
  DatabaseSettings plain;
  plain.fps = 120.0;
  const std::string good = folder.write("good.toml", R"([[clip]]
file = "16_16.bvh"
ranges = [{ first_frame = 151, last_frame = 260, tags = ["turn"] }]
)");
  auto ranged = load_database({good}, plain);
  ASSERT_TRUE(ranged) << ranged.error().to_string();
  ASSERT_EQ(ranged->clips.size(), 2u);
  ASSERT_EQ(ranged->tag_ranges.size(), 2u);
  EXPECT_EQ(ranged->tag_ranges[0].first_frame, 150);  // file frames 151..200
  EXPECT_EQ(ranged->tag_ranges[0].frame_count, 50);
  EXPECT_EQ(ranged->tag_ranges[1].first_frame, 200);  // 211..260, the second part's first 50
  EXPECT_EQ(ranged->tag_ranges[1].frame_count, 50);
  const std::string bad = folder.write("bad.toml", R"([[clip]]
file = "16_16.bvh"
ranges = [
  { first_frame = 1, last_frame = 10, tags = ["walk"] },
  { first_frame = 202, last_frame = 209, tags = ["stop"] },
]
)");
  auto refused = load_database({bad}, plain);
  ASSERT_FALSE(refused);
  EXPECT_EQ(refused.error().line, 5);
  EXPECT_NE(refused.error().message.find(fmt::format("range 202..209 holds only frames the reader drops from {} "
                                                     "(between capture glitches within it; --keep-rest-frames keeps "
                                                     "them); the clip's frames are 1..200, 211..{}", file, n)),
            std::string::npos)
      << refused.error().to_string();
  // Kept whole when asked.
  plain.keep_rest_frames = true;
  DatabaseLoadNotes kept_notes;
  auto kept = load_database({file}, plain, &kept_notes);
  ASSERT_TRUE(kept) << kept.error().to_string();
  ASSERT_EQ(kept->clips.size(), 1u);
  EXPECT_EQ(kept->clips[0].frame_count, n);
  EXPECT_TRUE(kept_notes.glitch_splits.empty());
}

TEST(DatabaseLoader, GlitchesWithinAClipAreNumberedInItsFile) {
  // 16_16 opening on 10 frames of its arm elsewhere (cut off on reading: glitched_ends.h) and
  // with the arm elsewhere again in the file's frames 201..210; a manifest keeps frames 51 on.
  // The glitches and parts are the file's frames, the ranges land on each part's frames, and at
  // 30 fps each part lasts as long as its frames.
  TempFolder folder("numbered");
  const Clip clean = test::load_whole_data_clip("cmu/16/16_16.amc");
  const int n = clean.motion.frame_count;
  const Clip glitched = test::with_turn(test::with_turn(clean, "rhumerus", 0, 9, 1.745), "rhumerus", 200, 209, 1.745);
  folder.write("lead.bvh", write_bvh(glitched.skeleton, glitched.motion, BvhWriteSettings{}));
  const std::string manifest = folder.write("lead.toml", R"([[clip]]
file = "lead.bvh"
first_frame = 51
ranges = [{ first_frame = 181, last_frame = 230, tags = ["turn"] }]
)");
  auto read_at = [](const std::string& input, double fps, DatabaseLoadNotes& notes) {
    DatabaseSettings settings;
    settings.fps = fps;
    return load_database({input}, settings, &notes);
  };
  for (const double fps : {120.0, 30.0}) {
    DatabaseLoadNotes notes;
    auto db = read_at(manifest, fps, notes);
    ASSERT_TRUE(db) << db.error().to_string();
    ASSERT_EQ(notes.glitched_ends.size(), 1u);
    EXPECT_EQ(notes.glitched_ends[0].leading, 10);
    ASSERT_EQ(notes.glitch_splits.size(), 1u);
    const DatabaseLoadNotes::GlitchSplit& split = notes.glitch_splits[0];
    ASSERT_EQ(split.glitches.size(), 2u);
    EXPECT_EQ(split.glitches[0].frame, 200);
    EXPECT_DOUBLE_EQ(split.glitches[0].seconds, 200.0 / 120.0);
    EXPECT_EQ(split.glitches[1].frame, 210);
    ASSERT_EQ(split.parts.size(), 2u);
    EXPECT_EQ(split.parts[0].first_frame, 51);
    EXPECT_EQ(split.parts[0].last_frame, 200);
    EXPECT_EQ(split.parts[1].first_frame, 211);
    EXPECT_EQ(split.parts[1].last_frame, n);
    EXPECT_EQ(split.dropped_frames, 10);
    ASSERT_EQ(db->clips.size(), 2u);
    const double step = 120.0 / fps;  // file frames per database frame
    EXPECT_NEAR(db->clips[0].frame_count, (200 - 51) / step + 1, 1.0);
    EXPECT_NEAR(db->clips[1].frame_count, (n - 211) / step + 1, 1.0);
    if (fps == 120.0) {  // frames are frames: the part is the file from frame 211 on
      for (int j = 0; j < clean.motion.joint_count; ++j) {
        EXPECT_TRUE(db->clips[1].motion.rotations(0)[j].isApprox(clean.motion.rotations(210)[j], 1e-6)) << j;
      }
    }
    // The range 181..230: the first part's file frames 181..200, the second's 211..230.
    ASSERT_EQ(db->tag_ranges.size(), 2u);
    EXPECT_NEAR(db->tag_ranges[0].first_frame, (181 - 51) / step, 1.0);
    EXPECT_EQ(db->tag_ranges[0].first_frame + db->tag_ranges[0].frame_count, db->clips[0].frame_count);
    EXPECT_EQ(db->tag_ranges[1].first_frame, db->clips[1].first_frame);
    EXPECT_NEAR(db->tag_ranges[1].frame_count, (230 - 211) / step + 1, 1.0);
  }
  // Frames 197..204 hold the step out after frame 200: parts of 4 frames, none a quarter second
  // long, so the first (the clip's own end) stays at 120 fps; at 30 fps it is under 2 frames and
  // the frames are read whole.
  const std::string short_range = folder.write("short.toml", R"([[clip]]
file = "lead.bvh"
first_frame = 197
last_frame = 204
)");
  for (const double fps : {120.0, 30.0}) {
    DatabaseLoadNotes notes;
    auto db = read_at(short_range, fps, notes);
    ASSERT_TRUE(db) << db.error().to_string();
    ASSERT_EQ(db->clips.size(), 1u);
    EXPECT_EQ(db->clips[0].frame_count, fps == 120.0 ? 4 : 2);
    EXPECT_EQ(notes.glitch_splits.size(), fps == 120.0 ? 1u : 0u);
  }
}

TEST(DatabaseLoader, RangesCoverTheFramesAGlitchLeavesAtAClipsEnd) {
  // 16_16 with its last three frames' right upper arm turned by 100 degrees (a glitch before
  // them, cut off on reading): a range to the file's last frame covers the clip to its new end;
  // one wholly in the frames cut off is an error saying why, at its line.
  TempFolder folder("tail");
  Clip clip = test::load_whole_data_clip("cmu/16/16_16.amc");
  const int n = clip.motion.frame_count;
  const int arm = clip.skeleton.find("rhumerus").value_or(0);
  for (int f = n - 3; f < n; ++f) {
    Quat& q = clip.motion.rotations(f)[arm];
    q = (q * Quat(Eigen::AngleAxisd(1.745, Vec3::UnitX()))).normalized();
  }
  folder.write("tail.bvh", write_bvh(clip.skeleton, clip.motion, BvhWriteSettings{}));
  DatabaseSettings settings;
  settings.fps = 120.0;  // the file's rate: frames are frames
  const std::string good = folder.write("good.toml", fmt::format(R"([[clip]]
file = "tail.bvh"
ranges = [{{ first_frame = 1, last_frame = {0}, tags = ["walk"] }}]
)", n));
  DatabaseLoadNotes notes;
  auto db = load_database({good}, settings, &notes);
  ASSERT_TRUE(db) << db.error().to_string();
  ASSERT_EQ(db->clips.size(), 1u);
  EXPECT_EQ(db->clips[0].frame_count, n - 3);
  ASSERT_EQ(notes.glitched_ends.size(), 1u);
  EXPECT_EQ(notes.glitched_ends[0].leading, 0);
  EXPECT_EQ(notes.glitched_ends[0].trailing, 3);
  ASSERT_EQ(db->tag_ranges.size(), 1u);
  EXPECT_EQ(db->tag_ranges[0].first_frame, 0);
  EXPECT_EQ(db->tag_ranges[0].frame_count, n - 3);
  const std::string bad = folder.write("bad.toml", fmt::format(R"([[clip]]
file = "tail.bvh"
ranges = [
  {{ first_frame = 1, last_frame = 10, tags = ["walk"] }},
  {{ first_frame = {0}, last_frame = {1}, tags = ["stop"] }},
]
)", n - 1, n));
  auto refused = load_database({bad}, settings);
  ASSERT_FALSE(refused);
  EXPECT_EQ(refused.error().line, 5);
  EXPECT_NE(refused.error().message.find(fmt::format("range {}..{} holds only frames the reader drops from", n - 1, n)),
            std::string::npos)
      << refused.error().to_string();
  EXPECT_NE(refused.error().message.find(fmt::format("tail.bvh (cut off by a capture glitch; --keep-rest-frames keeps "
                                                     "them); the clip's frames are 1..{}", n - 3)),
            std::string::npos)
      << refused.error().to_string();
  settings.keep_rest_frames = true;
  auto kept = load_database({bad}, settings);
  ASSERT_TRUE(kept) << kept.error().to_string();
  EXPECT_EQ(kept->clips[0].frame_count, n);
}

TEST(DatabaseLoader, NotesTheRestFramesItDroppedOnceAFile) {
  // 07_01.bvh opens on a converter's T-pose frame, 07_12.bvh on two: two clips cut from the one
  // and the other whole note each file once, with the frames dropped; kept, none.
  TempFolder folder("rest");
  const std::string manifest = folder.write("rest.toml", fmt::format(R"([[clip]]
file = "{0}"
name = "first"
last_frame = 150
[[clip]]
file = "{0}"
name = "second"
first_frame = 151
[[clip]]
file = "{1}"
)", folder.relative_data("bvh/07_01.bvh"), folder.relative_data("bvh/07_12.bvh")));
  DatabaseSettings settings;
  settings.fps = 120.0;  // the files' rate
  DatabaseLoadNotes notes;
  auto db = load_database({manifest}, settings, &notes);
  ASSERT_TRUE(db) << db.error().to_string();
  ASSERT_EQ(db->clips.size(), 3u);
  ASSERT_EQ(notes.rest_frames.size(), 2u);
  EXPECT_NE(notes.rest_frames[0].file.find("07_01.bvh"), std::string::npos) << notes.rest_frames[0].file;
  EXPECT_EQ(notes.rest_frames[0].frames, 1);
  EXPECT_NE(notes.rest_frames[1].file.find("07_12.bvh"), std::string::npos) << notes.rest_frames[1].file;
  EXPECT_EQ(notes.rest_frames[1].frames, 2);
  settings.keep_rest_frames = true;
  DatabaseLoadNotes kept;
  auto all = load_database({manifest}, settings, &kept);
  ASSERT_TRUE(all) << all.error().to_string();
  EXPECT_TRUE(kept.rest_frames.empty());
  // At the files' rate, the kept frames are there: the first clip starts at the file's first
  // frame, the whole 07_12 has its two back.
  ASSERT_EQ(all->clips.size(), 3u);
  EXPECT_EQ(all->clips[0].frame_count, db->clips[0].frame_count + 1);
  EXPECT_EQ(all->clips[1].frame_count, db->clips[1].frame_count);
  EXPECT_EQ(all->clips[2].frame_count, db->clips[2].frame_count + 2);
  EXPECT_TRUE(notes.glitched_ends.empty());  // their motion, the T-pose dropped, has no glitch at its ends
}

TEST(DatabaseLoader, RejectsASkeletonOfOtherJoints) {
  const std::string bvh = test::data_path("bvh/07_01.bvh");
  auto db = load_database({test::data_path("cmu/16"), bvh}, cmu_settings());
  ASSERT_FALSE(db);
  EXPECT_EQ(db.error().file, bvh);
  const std::string& message = db.error().message;
  EXPECT_NE(message.find("does not match"), std::string::npos) << message;
  EXPECT_NE(message.find("16.asf"), std::string::npos) << message;
  EXPECT_NE(message.find("names and parents"), std::string::npos) << message;
  EXPECT_NE(message.find("joint 0 is 'root' there, 'hip' here"), std::string::npos) << message;  // the first difference
  EXPECT_NE(message.find("they share no joint"), std::string::npos) << message;  // roots of other names
  EXPECT_NE(message.find("the roots are 'root' and 'hip'"), std::string::npos) << message;
}

TEST(DatabaseLoader, RejectsSkeletonsWhoseSharedJointsLackAnAnkle) {
  // Most joints shared, but one file has fingers and its left ankle renamed: the shared joints
  // cannot carry the feet, and the error says so. (With the ankle renamed alone, the hierarchy
  // is the same, matched by place: ReadsTheFirstRigUnderOtherNamesAndInAnotherRestPose.)
  TempFolder folder("ankle");
  const Clip walk = test::load_data_clip("cmu/16/16_15.amc");
  const Clip fingers = test::with_fingers(walk);
  const std::string plain = folder.write("a.bvh", write_bvh(walk.skeleton, walk.motion, BvhWriteSettings{}));
  const std::string renamed = folder.write(
      "b.bvh", test::replace_once(write_bvh(fingers.skeleton, fingers.motion, BvhWriteSettings{}), "JOINT lfoot",
                                  "JOINT lpes"));
  auto db = load_database({plain, renamed}, cmu_settings());
  ASSERT_FALSE(db);
  EXPECT_EQ(db.error().file, renamed);
  EXPECT_NE(db.error().message.find("the ankle 'lfoot' is not among the"), std::string::npos) << db.error().message;
}

// The clip on `names`' joint names (the same hierarchy) and resting as `rest` (the same joints),
// every joint where it was: what another converter of the same capture writes.
Clip as_other_rig(const Clip& clip, const Skeleton& names, const Skeleton& rest) {
  return renamed_as(on_rest_pose_of(clip, rest), names);
}

TEST(DatabaseLoader, ReadsTheFirstRigUnderOtherNamesAndInAnotherRestPose) {
  // A walk written as CMU's names, and another walk as a converter that names the joints as
  // MotionBuilder does (111_36.bvh) and hangs the arms down (131_01.bvh's rest pose): one
  // library, every clip on the first's names and rest pose, every joint where its file has it.
  TempFolder folder("rigs");
  const Clip cmu = test::load_data_clip("bvh/16_01.bvh", 0.056444);
  const Clip walk = test::load_data_clip("cmu/16/16_15.amc");
  ASSERT_EQ(hierarchy_mismatch(cmu.skeleton, walk.skeleton), std::nullopt);  // AMC and its conversion
  const Clip other = as_other_rig(test::load_data_clip("cmu/16/16_16.amc"),
                                  test::load_data_clip("bvh/111_36.bvh").skeleton,
                                  test::load_data_clip("bvh/131_01.bvh").skeleton);
  const std::string first = folder.write("a.bvh", write_bvh(walk.skeleton, walk.motion, BvhWriteSettings{}));
  const std::string second = folder.write("b.bvh", write_bvh(other.skeleton, other.motion, BvhWriteSettings{}));

  DatabaseLoadNotes notes;
  auto db = load_database({first, second}, cmu_settings(), &notes);
  ASSERT_TRUE(db) << db.error().to_string();
  ASSERT_EQ(db->skeletons.size(), 2u);
  for (int j = 0; j < db->skeletons[0].joint_count(); ++j) {
    EXPECT_EQ(db->skeletons[1].joint(j).name, db->skeletons[0].joint(j).name);
  }
  EXPECT_LT(rest_pose_difference(db->skeletons[0], db->skeletons[1]).angle_deg, kRestPoseRetargetDeg);
  ASSERT_EQ(notes.matched_rigs.size(), 1u);
  const DatabaseLoadNotes::MatchedRig& rig = notes.matched_rigs[0];
  EXPECT_EQ(rig.file, second);
  const std::pair<std::string, std::string> thigh("LeftUpLeg", "lfemur");
  EXPECT_NE(std::find(rig.renamed.begin(), rig.renamed.end(), thigh), rig.renamed.end());
  ASSERT_TRUE(rig.rest_pose.has_value());
  EXPECT_NEAR(rig.rest_pose->angle_deg, 90.0, 5.0);
  const std::vector<std::string> warnings = load_warnings(notes);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("b.bvh: its joints are the library's first rig's under other names, matched by their "
                             "place in the hierarchy (Hips as root, LHipJoint as lhipjoint, LeftUpLeg as lfemur, 31 "
                             "in all)"),
            std::string::npos)
      << warnings[0];
  EXPECT_NE(warnings[0].find("re-expressed on that rest pose"), std::string::npos) << warnings[0];
  // Every joint where the file alone has it, and the feet found on the first's names.
  auto alone = load_database({second}, cmu_settings());
  ASSERT_TRUE(alone) << alone.error().to_string();
  EXPECT_LT(test::max_position_error(world_positions(db->skeletons[1], db->clips[1].motion),
                                     world_positions(alone->skeletons[0], alone->clips[0].motion)),
            1e-9);
  EXPECT_FALSE(db->frame_contacts.empty());
  // Synthesis plays every clip's rotations on one skeleton: on the first's, each bone of the
  // second clip points where its own skeleton has it (as read, its forearms would hang 90
  // degrees off).
  const auto largest_bone_turn = [&](const Skeleton& played_on, const Motion& motion, const Skeleton& own) {
    const std::vector<Vec3> a = world_positions(played_on, motion);
    const std::vector<Vec3> b = world_positions(own, motion);
    const auto joints = static_cast<size_t>(own.joint_count());
    double worst = 0.0;
    for (size_t f = 0; f < a.size() / joints; ++f) {
      for (int j = 1; j < own.joint_count(); ++j) {
        const size_t i = f * joints + static_cast<size_t>(j);
        const size_t p = f * joints + static_cast<size_t>(own.parent(j));
        const Vec3 u = a[i] - a[p], v = b[i] - b[p];
        if (u.norm() < 0.01 || v.norm() < 0.01) continue;
        worst = std::max(worst, std::acos(std::clamp(u.normalized().dot(v.normalized()), -1.0, 1.0)));
      }
    }
    return worst * 180.0 / 3.141592653589793;
  };
  const double turned = largest_bone_turn(db->skeletons[0], db->clips[1].motion, db->skeletons[1]);
  const double as_read = largest_bone_turn(db->skeletons[0], alone->clips[0].motion, alone->skeletons[0]);
  EXPECT_GT(as_read, 60.0);
  EXPECT_LT(turned, 1.0) << "as read " << as_read;
  // The first file alone, or the library of one rig, is read as before: nothing noted.
  DatabaseLoadNotes plain_notes;
  ASSERT_TRUE(load_database({first, first}, cmu_settings(), &plain_notes));
  EXPECT_TRUE(plain_notes.matched_rigs.empty());
}

TEST(DatabaseLoader, ClipsThatLoopArePlayedOnPastTheirEnd) {
  // A walk cycle whose first frame follows its last, and one whose last frame repeats its first
  // (at 30 fps, the database's rate): each goes on for a window and a frame (11 at 30 fps), as
  // the cycle carries on; a capture does not, nor a cycle cut from a longer file by a manifest,
  // and with loops off neither does a cycle.
  TempFolder folder("loops");
  Clip walk = test::load_data_clip("cmu/16/16_15.amc");
  walk.motion = *resample(walk.motion, 30.0);
  const Clip following = test::loop_of(walk, 32, 34, false);
  const Clip repeating = test::loop_of(walk, 32, 34, true);
  const std::vector<std::string> files = {
      folder.write("following.bvh", write_bvh(following.skeleton, following.motion, BvhWriteSettings{})),
      folder.write("repeating.bvh", write_bvh(repeating.skeleton, repeating.motion, BvhWriteSettings{})),
      test::data_path("bvh/16_01.bvh")};
  DatabaseSettings settings = cmu_settings();
  DatabaseLoadNotes notes;
  auto db = load_database(files, settings, &notes);
  ASSERT_TRUE(db) << db.error().to_string();
  ASSERT_EQ(notes.loops.size(), 2u);
  EXPECT_EQ(notes.loops[0].clip, "following");
  EXPECT_FALSE(notes.loops[0].choice.last_repeats_first);
  EXPECT_EQ(notes.loops[0].choice.period, 34);
  EXPECT_TRUE(notes.loops[1].choice.last_repeats_first);
  EXPECT_EQ(notes.loops[1].choice.period, 34);
  EXPECT_EQ(settings.loop_frames_at(30.0), 11);
  EXPECT_EQ(notes.loops[0].added_frames, 11);  // a window (10 frames at 30 fps) and a frame
  EXPECT_EQ(db->clips[0].frame_count, 34 + 11);
  EXPECT_EQ(db->clips[1].frame_count, 35 + 11);
  // The frames added are the cycle's first, moved on by one cycle: the same pose about the root.
  const std::vector<Vec3> played = world_positions(db->skeletons[0], db->clips[0].motion);
  const auto joints = static_cast<size_t>(db->skeletons[0].joint_count());
  for (size_t j = 1; j < joints; ++j) {
    const Vec3 start = played[j] - played[0];
    const Vec3 again = played[34 * joints + j] - played[34 * joints];
    EXPECT_LT((start - again).norm(), 0.02) << j;  // the root does not turn in this cycle
  }
  EXPECT_EQ(db->frame_contacts.size(), static_cast<size_t>(db->frame_count()));

  // One stride of the walk itself, cut by a manifest, is nearly a loop (its seam 2.6 median
  // departures), but the file goes on: it is not judged.
  const Clip whole_walk = [&] {
    Clip c = walk;
    c.motion = walk.motion.slice(0, 100);
    return c;
  }();
  ASSERT_TRUE(find_loop(walk.skeleton, walk.motion.slice(32, 34)).loops);
  const std::string walk_file =
      folder.write("walk30.bvh", write_bvh(whole_walk.skeleton, whole_walk.motion, BvhWriteSettings{}));
  const std::string cut = folder.write(
      "cut.toml", fmt::format("[[clip]]\nfile = \"{}\"\nfirst_frame = 33\nlast_frame = 66\n", walk_file));
  DatabaseLoadNotes cut_notes;
  auto cut_db = load_database({cut}, settings, &cut_notes);
  ASSERT_TRUE(cut_db) << cut_db.error().to_string();
  EXPECT_TRUE(cut_notes.loops.empty());
  EXPECT_EQ(cut_db->clips[0].frame_count, 34);

  settings.loops = false;
  DatabaseLoadNotes off_notes;
  auto off = load_database(files, settings, &off_notes);
  ASSERT_TRUE(off) << off.error().to_string();
  EXPECT_TRUE(off_notes.loops.empty());
  EXPECT_EQ(off->clips[0].frame_count, 34);
  settings.loops = true;
  settings.loop_overlap_frames = 4;
  DatabaseLoadNotes short_notes;
  ASSERT_TRUE(load_database(files, settings, &short_notes));
  EXPECT_EQ(short_notes.loops[0].added_frames, 4);
  settings.loop_overlap_frames = -1;
  EXPECT_FALSE(load_database(files, settings));
}

TEST(DatabaseLoader, JointsOfTheFirstsNamesInAnotherOrderAreMatchedByName) {
  // Names that say no side (bone0, bone1, ...), the legs listed the other way round in the second
  // file: the same parents by index, but every name is the first's, so each joint keeps its name
  // (matching by place would swap the legs).
  TempFolder folder("order");
  const Clip walk = test::load_data_clip("cmu/16/16_15.amc");
  std::vector<std::pair<int, std::string>> neutral;
  for (int j = 0; j < walk.skeleton.joint_count(); ++j) neutral.emplace_back(j, fmt::format("bone{}", j));
  Clip plain = walk;
  {
    std::vector<JointDef> joints(walk.skeleton.joints().begin(), walk.skeleton.joints().end());
    for (const auto& [j, name] : neutral) joints[static_cast<size_t>(j)].name = name;
    plain.skeleton = Skeleton(std::move(joints));
  }
  const int left_hip = *walk.skeleton.find("lhipjoint");
  const int right_hip = *walk.skeleton.find("rhipjoint");
  const auto below = [&](int top, int j) {
    for (; j >= 0; j = walk.skeleton.parent(j)) {
      if (j == top) return true;
    }
    return false;
  };
  std::vector<std::string> order{"bone0"};
  for (const bool end_sites : {false, true}) {  // the joints, then the end sites (listed last), each
    for (const bool right_leg : {true, false}) {  // the right leg's first
      for (int j = 1; j < walk.skeleton.joint_count(); ++j) {
        if (walk.skeleton.joint(j).end_site == end_sites && below(right_hip, j) == right_leg) {
          order.push_back(fmt::format("bone{}", j));
        }
      }
    }
  }
  ASSERT_TRUE(below(left_hip, left_hip + 1));
  auto reordered = keep_joints(plain, order);
  ASSERT_TRUE(reordered) << reordered.error().to_string();
  ASSERT_EQ(hierarchy_mismatch(plain.skeleton, reordered->skeleton), std::nullopt);  // the legs look alike
  const std::string first = folder.write("a.bvh", write_bvh(plain.skeleton, plain.motion, BvhWriteSettings{}));
  const std::string second =
      folder.write("b.bvh", write_bvh(reordered->skeleton, reordered->motion, BvhWriteSettings{}));
  DatabaseLoadNotes notes;
  auto db = load_database({first, second}, cmu_settings(), &notes);
  ASSERT_TRUE(db) << db.error().to_string();
  EXPECT_TRUE(notes.matched_rigs.empty());
  auto alone = load_database({second}, cmu_settings());
  ASSERT_TRUE(alone) << alone.error().to_string();
  Clip in_library, read_alone;
  in_library.skeleton = db->skeletons[1];
  in_library.motion = db->clips[1].motion;
  read_alone.skeleton = alone->skeletons[0];
  read_alone.motion = alone->clips[0].motion;
  EXPECT_LT(test::max_position_error_by_name(in_library, read_alone), 1e-9);
}

TEST(DatabaseLoader, RejectsTheSameHierarchyWithItsSidesNamedTheOtherWay) {
  TempFolder folder("sides");
  const Clip walk = test::load_data_clip("cmu/16/16_15.amc");
  const std::string text = write_bvh(walk.skeleton, walk.motion, BvhWriteSettings{});
  const std::string first = folder.write("a.bvh", text);
  const std::string swapped = folder.write(
      "b.bvh", test::replace_once(test::replace_once(text, "JOINT lfemur", "JOINT RightUpLeg"), "JOINT rfemur",
                                  "JOINT LeftUpLeg"));
  auto db = load_database({first, swapped}, cmu_settings());
  ASSERT_FALSE(db);
  EXPECT_EQ(db.error().file, swapped);
  EXPECT_NE(db.error().message.find("nor is it the same hierarchy under other names: joint 2 is 'lfemur' (left) "
                                    "there and 'RightUpLeg' (right) here"),
            std::string::npos)
      << db.error().message;
}

TEST(DatabaseLoader, ErrorsNameTheFileAndManifestLine) {
  TempFolder folder("errors");
  const std::string amc = folder.relative_data("cmu/16/16_15.amc");
  struct Case {
    const char* rule;
    std::string manifest_text;
    int line;
    const char* message_part;
  };
  const std::vector<Case> cases = {
      {"clip file missing", "[[clip]]\n\nfile = \"nowhere/16_99.amc\"\n", 3, "not found"},
      {"skeleton file missing", fmt::format("skeleton = \"none.asf\"\n[[clip]]\nfile = \"{}\"\n", amc), 1, "none.asf not found"},
      {"range past the end", fmt::format("[[clip]]\nfile = \"{}\"\nfirst_frame = 100\nlast_frame = 9000\n", amc), 4,
       "past the end"},
      {"range tags past the end",
       fmt::format("[[clip]]\nfile = \"{}\"\nranges = [\n {{ first_frame = 1, last_frame = 9000, tags = [\"a\"] }},\n]\n", amc), 4,
       "past the end"},
      {"too short after resampling", fmt::format("[[clip]]\nfile = \"{}\"\nfirst_frame = 10\nlast_frame = 12\n", amc), 1,
       "needs at least 2"},
      {"only dropped rest frames",
       fmt::format("[[clip]]\nfile = \"{}\"\nlast_frame = 1\n", folder.relative_data("bvh/07_01.bvh")), 3, "drops"},
      {"manifest syntax", "[[clip]\n", 1, "TOML"},
  };
  for (const Case& c : cases) {
    const std::string manifest = folder.write("bad.toml", c.manifest_text);
    auto db = load_database({manifest}, cmu_settings());
    ASSERT_FALSE(db) << c.rule;
    EXPECT_EQ(db.error().file, manifest) << c.rule;
    EXPECT_EQ(db.error().line, c.line) << c.rule << ": " << db.error().to_string();
    EXPECT_NE(db.error().message.find(c.message_part), std::string::npos) << c.rule << ": " << db.error().to_string();
  }
}

TEST(DatabaseLoader, ShortClipIsAnErrorNamingTheFile) {
  // The first 3 frames of a clip: 2/120 s, 1 frame at 30 fps.
  TempFolder folder("short");
  const std::string text = test::read_data("cmu/16/16_15.amc");
  const size_t cut = text.find("\n4\n");
  ASSERT_NE(cut, std::string::npos);
  const std::string amc = folder.write("16_15.amc", text.substr(0, cut + 1));
  folder.write("16.asf", test::read_data("cmu/16/16.asf"));
  auto db = load_database({amc}, cmu_settings());
  ASSERT_FALSE(db);
  EXPECT_EQ(db.error().file, amc);
  EXPECT_NE(db.error().message.find("1 frame at 30 fps (3 frames at 120 fps"), std::string::npos)
      << db.error().to_string();
}

// A BVH of a skeleton and no frames (Frames: 0): an error naming it, not a frame range "1..0"
// of a rest pose.
TEST(DatabaseLoader, AClipWithoutFramesIsAnErrorNamingTheFile) {
  TempFolder folder("noframes");
  const std::string text = test::read_data("bvh/07_01.bvh");
  const std::string bvh = folder.write("still.bvh", text.substr(0, text.find("MOTION")) +
                                                        "MOTION\nFrames: 0\nFrame Time: 0.008333\n");
  auto db = load_database({bvh, test::data_path("bvh/07_01.bvh")}, DatabaseSettings{});
  ASSERT_FALSE(db);
  EXPECT_EQ(db.error().file, bvh);
  EXPECT_EQ(db.error().message, "the clip has no frames (a skeleton without motion)");
}

// The rigs kept are read as loading reads them, in the library's order: a variant of Daz's rig
// first by name (an extra joint), Daz's own, Daz's under other names, and CMU's. Renamed as the
// first file's rig only, Daz's under other names cannot join the first: of the rigs that read
// together the Daz two are the most frames.
TEST(DatabaseLoader, TheRigsKeptReadTogetherInTheLibrarysOrder) {
  TempFolder folder("rig-order");
  const std::string daz = test::read_data("bvh/07_01.bvh");
  const size_t motion = daz.find("MOTION");
  const size_t hierarchy_end = daz.rfind('}', motion);
  std::string extra = daz.substr(0, hierarchy_end) +
                      "  JOINT prop\n  {\n    OFFSET 0 0 10\n    CHANNELS 3 Zrotation Xrotation Yrotation\n"
                      "    End Site\n    {\n      OFFSET 0 5 0\n    }\n  }\n" +
                      daz.substr(hierarchy_end, daz.find('\n', daz.find("Frame Time:")) + 1 - hierarchy_end);
  std::istringstream frames(daz.substr(daz.find('\n', daz.find("Frame Time:")) + 1));
  for (std::string line; std::getline(frames, line);) {
    if (!line.empty()) extra += line + " 0 0 0\n";
  }
  folder.write("a_extra.bvh", extra);
  folder.write("b_daz.bvh", daz);
  std::string renamed = daz;
  for (const char* joint : {"hip", "abdomen", "chest", "neck", "head", "leftEye", "rightEye"}) {
    renamed = test::replace_once(renamed, fmt::format("{}\n", joint), fmt::format("{}_z\n", joint));
  }
  folder.write("c_renamed.bvh", renamed);
  // CMU's rig, 100 frames (fewer than the Daz two's 158).
  const std::string cmu = test::read_data("bvh/16_01.bvh");
  const size_t frames_at = cmu.find("Frames:");
  size_t end = cmu.find('\n', cmu.find("Frame Time:")) + 1;
  for (int f = 0; f < 100; ++f) end = cmu.find('\n', end) + 1;
  folder.write("d_cmu.bvh", cmu.substr(0, frames_at) + "Frames: 100" +
                                cmu.substr(cmu.find('\n', frames_at), end - cmu.find('\n', frames_at)));
  DatabaseLoadNotes notes;
  auto db = load_database({folder.path().string()}, cmu_settings(), &notes);
  ASSERT_TRUE(db) << db.error().to_string();
  std::vector<std::string> names;
  for (const DatabaseClip& clip : db->clips) names.push_back(clip.name);
  EXPECT_EQ(names, (std::vector<std::string>{"a_extra", "b_daz"}));
  ASSERT_EQ(notes.other_rigs.size(), 1u);
  EXPECT_EQ(notes.other_rigs[0].files, (std::vector<std::string>{(folder.path() / "c_renamed.bvh").string(),
                                                                   (folder.path() / "d_cmu.bvh").string()}));
}

// A folder's file of a pose (no frame, or one: a T-pose export) is passed over, noted; the
// library is its other files, as without it.
TEST(DatabaseLoader, AFoldersPoseFilesArePassedOver) {
  TempFolder folder("poses");
  const std::string text = test::read_data("bvh/07_01.bvh");
  const std::string hierarchy = text.substr(0, text.find("MOTION"));
  const size_t first_line = text.find('\n', text.find("Frame Time:")) + 1;
  const std::string one_frame = text.substr(first_line, text.find('\n', first_line) + 1 - first_line);
  const std::string still = folder.write("00_still.bvh", hierarchy + "MOTION\nFrames: 0\nFrame Time: 0.008333\n");
  const std::string tpose =
      folder.write("00_tpose.bvh", hierarchy + "MOTION\nFrames: 1\nFrame Time: 0.008333\n" + one_frame);
  folder.write("07_01.bvh", text);
  DatabaseLoadNotes notes;
  auto db = load_database({folder.path().string()}, cmu_settings(), &notes);
  ASSERT_TRUE(db) << db.error().to_string();
  ASSERT_EQ(db->clips.size(), 1u);
  EXPECT_EQ(db->clips[0].name, "07_01");
  ASSERT_EQ(notes.poses.size(), 2u);
  EXPECT_EQ(notes.poses[0].file, still);
  EXPECT_EQ(notes.poses[0].frames, 0);
  EXPECT_EQ(notes.poses[1].file, tpose);
  EXPECT_EQ(notes.poses[1].frames, 1);
  EXPECT_DOUBLE_EQ(notes.poses[1].fps, 120.0);
  // Nothing else of them is noted: the unit read is the motion's file's alone.
  ASSERT_EQ(notes.detected_units.size(), 1u);
  EXPECT_EQ(notes.detected_units[0].file, (folder.path() / "07_01.bvh").string());
  EXPECT_EQ(load_warnings(notes).front(),
            fmt::format("2 files passed over, a pose rather than a motion (under 2 frames at the library's rate): {} "
                        "(0 frames at 120 fps), {} (1 frame at 120 fps)",
                        still, tpose));
  const auto alone = load_database({test::data_path("bvh/07_01.bvh")}, cmu_settings());
  ASSERT_TRUE(alone);
  EXPECT_EQ(db->clips[0].frame_count, alone->clips[0].frame_count);
  EXPECT_EQ(db->skeletons[0].joint_count(), alone->skeletons[0].joint_count());

  // Given themselves, errors; a folder of poses only, an error naming its first file.
  auto named = load_database({tpose, test::data_path("bvh/07_01.bvh")}, cmu_settings());
  ASSERT_FALSE(named);
  EXPECT_EQ(named.error().file, tpose);
  fs::remove(folder.path() / "07_01.bvh");
  auto poses = load_database({folder.path().string()}, cmu_settings());
  ASSERT_FALSE(poses);
  EXPECT_EQ(poses.error().file, still);
  EXPECT_NE(poses.error().message.find("every clip file of the folder holds a pose"), std::string::npos)
      << poses.error().message;
}

// A folder's file that cannot be read (cut short; another format under the extension) is passed
// over with the error reading it gives, once, however often the clips are read; the library is its
// other files, as without it. Named itself, the file is an error; a folder of such files only
// stops with the first one's error.
TEST(DatabaseLoader, AFoldersUnreadableFilesArePassedOver) {
  TempFolder folder("unreadable");
  const std::string text = test::read_data("bvh/07_01.bvh");
  const std::string cut = folder.write("00_cut.bvh", text.substr(0, text.find("MOTION") / 2));
  const std::string other = folder.write("01_other.bvh", "{\"not\": \"a bvh\"}\n");
  folder.write("07_01.bvh", text);
  folder.write("07_12.bvh", test::read_data("bvh/07_12.bvh"));
  const auto alone = load_database({test::data_path("bvh/07_01.bvh"), test::data_path("bvh/07_12.bvh")},
                                   cmu_settings());
  ASSERT_TRUE(alone) << alone.error().to_string();
  const auto cut_alone = load_database({cut}, cmu_settings());
  ASSERT_FALSE(cut_alone);
  EXPECT_EQ(cut_alone.error().file, cut);
  EXPECT_GT(cut_alone.error().line, 0);
  DatabaseLoadNotes notes;
  auto db = load_database({folder.path().string()}, cmu_settings(), &notes);
  ASSERT_TRUE(db) << db.error().to_string();
  ASSERT_EQ(db->clips.size(), 2u);
  EXPECT_EQ(db->frame_count(), alone->frame_count());
  ASSERT_EQ(notes.unreadable.size(), 2u);
  EXPECT_EQ(notes.unreadable[0].to_string(), cut_alone.error().to_string());
  EXPECT_EQ(notes.unreadable[1].file, other);
  const std::vector<std::string> warnings = load_warnings(notes);
  EXPECT_NE(std::find(warnings.begin(), warnings.end(),
                      cut_alone.error().to_string() + " (passed over: the library is read without it)"),
            warnings.end());
  // Named itself, an error; a folder of them only, the first one's error.
  auto named = load_database({cut, test::data_path("bvh/07_01.bvh")}, cmu_settings());
  ASSERT_FALSE(named);
  EXPECT_EQ(named.error().to_string(), cut_alone.error().to_string());
  fs::remove(folder.path() / "07_01.bvh");
  fs::remove(folder.path() / "07_12.bvh");
  auto none = load_database({folder.path().string()}, cmu_settings());
  ASSERT_FALSE(none);
  EXPECT_EQ(none.error().file, cut);
  EXPECT_EQ(none.error().line, cut_alone.error().line);
  EXPECT_NE(none.error().message.find("and 1 other file of the folder could not be read either"), std::string::npos)
      << none.error().message;
}

TEST(DatabaseLoader, BadInputsAndSettings) {
  DatabaseSettings settings = cmu_settings();
  EXPECT_FALSE(load_database({}, settings));
  auto missing = load_database({test::data_path("cmu/nothing_here")}, settings);
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.error().message.find("no such file or folder"), std::string::npos);
  auto asf = load_database({test::data_path("cmu/16/16.asf")}, settings);
  ASSERT_FALSE(asf);
  EXPECT_NE(asf.error().message.find("skeleton only"), std::string::npos);
  TempFolder no_clips("no-clips");
  no_clips.write("notes.txt", "none\n");
  auto empty = load_database({no_clips.path().string()}, settings);
  ASSERT_FALSE(empty);
  EXPECT_NE(empty.error().message.find("no .amc, .bvh, .glb, .gltf or .fbx"), std::string::npos);
  auto tsv = load_database({test::data_path("cmu/cmu-mocap-index.tsv")}, settings);
  ASSERT_FALSE(tsv);
  EXPECT_NE(tsv.error().message.find("unknown input"), std::string::npos);

  DatabaseSettings bad_index = settings;
  bad_index.cmu_index_path = test::data_path("cmu/no-index.tsv");
  EXPECT_FALSE(load_database({test::data_path("cmu/16/16_15.amc")}, bad_index));

  const std::vector<std::pair<const char*, DatabaseSettings>> invalid = [&] {
    std::vector<std::pair<const char*, DatabaseSettings>> v;
    DatabaseSettings s = settings;
    s.fps = 0;
    v.emplace_back("fps", s);
    s.fps = 0.5;  // under build --fps's least
    v.emplace_back("fps", s);
    s.fps = 1001;
    v.emplace_back("fps", s);
    s = settings;
    s.bvh_metres_per_unit = -1;
    v.emplace_back("bvh_metres_per_unit", s);
    s = settings;
    s.input_fps = -5;
    v.emplace_back("input_fps", s);
    return v;
  }();
  for (const auto& [rule, s] : invalid) {
    auto status = s.validate();
    ASSERT_FALSE(status) << rule;
    EXPECT_NE(status.error().message.find(rule), std::string::npos) << status.error().message;
    EXPECT_FALSE(load_database({test::data_path("cmu/16/16_15.amc")}, s)) << rule;
  }
  EXPECT_TRUE(settings.validate());
}

// The feet: found by name, named by a manifest's [feet] or by the settings (which win); the
// contacts of every frame found with them; a rig without feet loads with the reason instead.
TEST(DatabaseLoader, TheFeetComeFromTheSettingsOrAManifestAndTheContactsWithThem) {
  auto found = load_database({test::data_path("cmu/16/16_15.amc")}, cmu_settings());
  ASSERT_TRUE(found) << found.error().to_string();
  EXPECT_TRUE(found->foot_names.empty());
  EXPECT_TRUE(found->contacts_error.empty());
  ASSERT_EQ(static_cast<int>(found->frame_contacts.size()), found->frame_count());
  EXPECT_EQ(found->frame_contacts, *database_contacts(*found));
  // A walk plants its feet, and not all the time.
  const long long planted = std::count_if(found->frame_contacts.begin(), found->frame_contacts.end(),
                                          [](ContactMask m) { return m != 0; });
  EXPECT_GT(planted, found->frame_count() / 2);

  // The shins named as ankles, by a manifest: other contacts, the ones those names give.
  TempFolder folder("feet");
  const std::string clip = folder.relative_data("cmu/16/16_15.amc");
  const std::string manifest = folder.write(
      "db.toml", fmt::format("[feet]\nleft_ankle = \"ltibia\"\nright_ankle = \"rtibia\"\n[[clip]]\nfile = \"{}\"\n", clip));
  auto named = load_database({manifest}, cmu_settings());
  ASSERT_TRUE(named) << named.error().to_string();
  const FootJointNames shins{"ltibia", "", "rtibia", ""};
  EXPECT_EQ(named->foot_names, shins);
  EXPECT_EQ(named->frame_contacts, *database_contacts(*named, {}, shins));
  EXPECT_NE(named->frame_contacts, found->frame_contacts);

  // The settings' names win over the manifest's.
  DatabaseSettings given = cmu_settings();
  given.foot_names = FootJointNames{"lfoot", "ltoes", "rfoot", "rtoes"};
  auto overridden = load_database({manifest}, given);
  ASSERT_TRUE(overridden) << overridden.error().to_string();
  EXPECT_EQ(overridden->foot_names, given.foot_names);
  EXPECT_EQ(overridden->frame_contacts, found->frame_contacts);

  // A joint named that the rig lacks: an error at the manifest's [feet] line, or for the settings.
  const std::string wrong = folder.write(
      "wrong.toml", fmt::format("fps = 30\n[feet]\nleft_ankle = \"LeftAnkle\"\n[[clip]]\nfile = \"{}\"\n", clip));
  auto missing = load_database({wrong}, cmu_settings());
  ASSERT_FALSE(missing);
  EXPECT_EQ(missing.error().file, wrong);
  EXPECT_EQ(missing.error().line, 2);
  EXPECT_NE(missing.error().message.find("LeftAnkle"), std::string::npos) << missing.error().to_string();
  given.foot_names = FootJointNames{"LeftAnkle", "", "", ""};
  auto missing_given = load_database({test::data_path("cmu/16/16_15.amc")}, given);
  ASSERT_FALSE(missing_given);
  EXPECT_NE(missing_given.error().message.find("LeftAnkle"), std::string::npos);

  // Two manifests naming other feet.
  auto clash = load_database({manifest, wrong}, cmu_settings());
  ASSERT_FALSE(clash);
  EXPECT_EQ(clash.error().file, wrong);
  EXPECT_NE(clash.error().message.find("one set of feet"), std::string::npos) << clash.error().to_string();
}

TEST(DatabaseLoader, ARigWithoutFeetLoadsWithTheReasonForNoContacts) {
  TempFolder folder("nofeet");
  std::string motion;
  for (int f = 0; f < 40; ++f) motion += fmt::format("{} 90 0 0 0 0 {} 0 0\n", 0.02 * f, f % 7);
  const std::string bvh = folder.write(
      "arm.bvh", "HIERARCHY\nROOT Base\n{\n  OFFSET 0 0 0\n  CHANNELS 6 Xposition Yposition Zposition Zrotation "
                 "Xrotation Yrotation\n  JOINT Arm\n  {\n    OFFSET 0 -50 0\n    CHANNELS 3 Zrotation Xrotation "
                 "Yrotation\n    End Site\n    {\n      OFFSET 0 -40 0\n    }\n  }\n}\nMOTION\nFrames: 40\nFrame "
                 "Time: 0.0333333\n" + motion);
  DatabaseSettings settings;
  settings.bvh_metres_per_unit = 0.01;
  auto db = load_database({bvh}, settings);
  ASSERT_TRUE(db) << db.error().to_string();
  EXPECT_TRUE(db->frame_contacts.empty());
  EXPECT_NE(db->contacts_error.find("ankle"), std::string::npos) << db->contacts_error;
  EXPECT_FALSE(contacts_of(*db));
}

}  // namespace
}  // namespace mg

namespace mg {
namespace {

// One take in two formats in a folder (a BVH and the glTF converted from it, CMU's AMC beside its
// BVH) is read once, from the capture's own format, with a warning; a clip given twice (a folder
// and a file of it, one file twice in a manifest) gets a name of its own, with a warning.
TEST(DatabaseLoader, OneTakeInTwoFormatsIsReadOnceAndEveryClipHasANameOfItsOwn) {
  TempFolder folder("formats");
  const std::string bvh_text = test::read_data("bvh/16_01.bvh");
  const std::string bvh = folder.write("16_01.bvh", bvh_text);
  const Clip clip = test::load_data_clip("bvh/16_01.bvh");
  auto glb = write_glb(clip.skeleton, clip.motion, "16_01");
  ASSERT_TRUE(glb);
  folder.write("16_01.glb", *glb);  // the glTF first in name order, the BVH kept
  auto other_glb = write_glb(clip.skeleton, clip.motion.slice(0, clip.motion.frame_count - 1), "16_05");
  ASSERT_TRUE(other_glb);
  folder.write("16_05.glb", *other_glb);  // another name: read
  DatabaseLoadNotes notes;
  auto db = load_database({folder.path().string()}, cmu_settings(), &notes);
  ASSERT_TRUE(db) << db.error().to_string();
  ASSERT_EQ(db->clips.size(), 2u);
  EXPECT_EQ(db->clips[0].name, "16_01");
  EXPECT_EQ(db->clips[0].source, bvh);
  EXPECT_EQ(db->clips[1].name, "16_05");
  ASSERT_EQ(notes.name_clashes.size(), 1u);
  EXPECT_NE(notes.name_clashes[0].find("16_01.glb left out: 16_01.bvh holds the clip of that name"), std::string::npos)
      << notes.name_clashes[0];
  EXPECT_EQ(load_warnings(notes).front(), notes.name_clashes[0]);

  // Inputs that overlap (the folder, the folder under another name, a file of it): each file
  // read once, said in one line.
  const std::string again = (folder.path() / "." / "").string();
  for (const std::vector<std::string>& inputs : {std::vector<std::string>{folder.path().string(), again, bvh},
                                                 std::vector<std::string>{folder.path().string(), bvh}}) {
    db = load_database(inputs, cmu_settings(), &notes);
    ASSERT_TRUE(db) << db.error().to_string();
    ASSERT_EQ(db->clips.size(), 2u);
    ASSERT_EQ(notes.name_clashes.size(), inputs.size());  // the .glb left out by each folder, then this
    EXPECT_EQ(notes.name_clashes.back(),
              inputs.size() == 3 ? fmt::format("3 files read once, reached by inputs that overlap: {} and 2 more", bvh)
                                 : fmt::format("1 file read once, reached by inputs that overlap: {}", bvh));
  }
  // A file given itself twice is read twice, the second clip 16_01_2; and so in a manifest that
  // reads one file twice without names.
  db = load_database({bvh, bvh}, cmu_settings(), &notes);
  ASSERT_TRUE(db) << db.error().to_string();
  ASSERT_EQ(db->clips.size(), 2u);
  EXPECT_EQ(db->clips[1].name, "16_01_2");
  ASSERT_EQ(notes.name_clashes.size(), 1u);
  EXPECT_NE(notes.name_clashes[0].find("a clip is named 16_01 already; this one is 16_01_2"), std::string::npos)
      << notes.name_clashes[0];
  const std::string manifest =
      folder.write("twice.toml", "[[clip]]\nfile = \"16_01.bvh\"\n[[clip]]\nfile = \"16_01.bvh\"\nlast_frame = 100\n");
  db = load_database({manifest}, cmu_settings(), &notes);
  ASSERT_TRUE(db) << db.error().to_string();
  ASSERT_EQ(db->clips.size(), 2u);
  EXPECT_EQ(db->clips[0].name, "16_01");
  EXPECT_EQ(db->clips[1].name, "16_01_2");
  ASSERT_EQ(notes.name_clashes.size(), 1u);
  EXPECT_NE(notes.name_clashes[0].find("twice.toml:3)"), std::string::npos) << notes.name_clashes[0];
}

TEST(DatabaseLoader, AFolderOfFoldersIsReadAsOneLibraryEachAmcWithItsSubjectsSkeleton) {
  TempFolder tree("tree");
  const std::string asf = test::read_data("cmu/16/16.asf");
  // Two takes of one name in two folders, and a copy of one in a third: read once.
  for (const auto& [subject, take] : {std::pair{"a", "16_15"}, {"b", "16_13"}, {"copy", "16_15"}}) {
    tree.write(fmt::format("{}/16.asf", subject), asf);
    tree.write(fmt::format("{}/16_15.amc", subject), test::read_data(fmt::format("cmu/16/{}.amc", take)));
  }
  // Two subjects' skeletons in one folder: each AMC takes its subject's, as CMU names them.
  tree.write("flat/07.asf", test::read_data("cmu/16/16.asf"));
  const std::string flat_asf = tree.write("flat/16.asf", asf);
  tree.write("flat/16_16.amc", test::read_data("cmu/16/16_16.amc"));
  // The BVH of a take read as AMC, in another folder: left out.
  tree.write("bvh/16_16.bvh", test::read_data("bvh/16_01.bvh"));
  DatabaseSettings settings = cmu_settings();
  settings.mirror = DatabaseSettings::Mirroring::kOff;  // its walks turn one way: as read
  DatabaseLoadNotes notes;
  auto db = load_database({tree.path().string()}, settings, &notes);
  ASSERT_TRUE(db) << db.error().to_string();
  ASSERT_EQ(db->clips.size(), 3u);
  EXPECT_EQ(db->clips[0].name, "a/16_15");
  EXPECT_EQ(db->clips[1].name, "b/16_15");
  EXPECT_EQ(db->clips[2].name, "16_16");
  EXPECT_EQ(db->clips[2].source, (tree.path() / "flat/16_16.amc").string());
  EXPECT_EQ(db->skeleton_names[static_cast<size_t>(db->clips[2].skeleton)], flat_asf);
  // CMU's tags come by the file's own name.
  for (int c = 0; c < 3; ++c) EXPECT_EQ(tags_of(*db, c), (std::set<std::string>{"walk"})) << c;
  EXPECT_EQ(db->clips[1].source, (tree.path() / "b/16_15.amc").string());
  EXPECT_NE(db->clips[1].frame_count, db->clips[0].frame_count);  // 16_13's frames
  EXPECT_EQ(notes.name_clashes, (std::vector<std::string>{
                                    fmt::format("{}: copy/16_15.amc left out: the same bytes as a/16_15.amc (a copy)",
                                                tree.path().string()),
                                    fmt::format("{}: bvh/16_16.bvh left out: flat/16_16.amc holds the clip of that "
                                                "name (one take in two formats?); a manifest can read both under "
                                                "names of their own",
                                                tree.path().string())}));

  // A folder of AMC files without its skeleton, or with skeletons named for no subject of them.
  fs::remove(tree.path() / "b/16.asf");
  db = load_database({tree.path().string()}, cmu_settings(), &notes);
  ASSERT_FALSE(db);
  EXPECT_EQ(db.error().file, (tree.path() / "b").string());
  EXPECT_NE(db.error().message.find("AMC files but no .asf skeleton"), std::string::npos) << db.error().message;
  fs::remove_all(tree.path() / "b");
  fs::rename(tree.path() / "flat/16.asf", tree.path() / "flat/17.asf");
  db = load_database({tree.path().string()}, cmu_settings(), &notes);
  ASSERT_FALSE(db);
  EXPECT_NE(db.error().message.find("2 .asf files and none is named as 16_16.amc's subject"), std::string::npos)
      << db.error().message;
}

// No file the command will write is read: a clip a folder holds or a manifest names, a manifest,
// an AMC's skeleton (given or found beside it). Each refused before anything is written, naming
// the output and how the file would be read; the library's other outputs are fine.
TEST(DatabaseLoader, AFileReadIsNoneOfTheOutputs) {
  TempFolder tree("outputs");
  const std::string asf = tree.write("mocap/16.asf", test::read_data("cmu/16/16.asf"));
  const std::string amc = tree.write("mocap/16_35.amc", test::read_data("cmu/16/16_35.amc"));
  const std::string manifest = tree.write("m.toml", "[[clip]]\nfile = \"mocap/16_35.amc\"\n");
  const auto refused = [&](const std::vector<std::string>& inputs, const std::string& output,
                           std::optional<std::string> asf_path = std::nullopt) {
    DatabaseSettings settings = cmu_settings();
    settings.asf_path = asf_path;
    settings.outputs = {(tree.path() / "g.mgraph").string(), output};
    auto db = load_database(inputs, settings);
    return db ? std::string() : db.error().file + ": " + db.error().message;
  };
  const std::string folder = (tree.path() / "mocap").string();
  EXPECT_EQ(refused({folder}, (tree.path() / "mocap/report.json").string()), "");
  EXPECT_EQ(refused({folder}, folder + "/./16_35.amc"),
            fmt::format("{}/./16_35.amc: is also an input ('{}', a clip file of a folder given): give the output "
                        "another name", folder, amc));
  EXPECT_NE(refused({folder}, asf).find(fmt::format("is also an input ('{}', the skeleton of {})", asf, amc)),
            std::string::npos);
  const std::string named = (tree.path() / "mocap/16_35.amc").string();
  EXPECT_NE(refused({manifest}, amc).find(fmt::format("('{}', a clip {} names)", named, manifest)), std::string::npos)
      << refused({manifest}, amc);
  EXPECT_NE(refused({manifest}, asf).find("the skeleton of"), std::string::npos);  // found beside the AMC
  EXPECT_NE(refused({manifest}, manifest).find("a manifest given"), std::string::npos);
  EXPECT_NE(refused({amc}, asf, asf).find("the skeleton of"), std::string::npos);  // given with --asf
  // None of them was written over.
  EXPECT_EQ(*read_text_file(amc), test::read_data("cmu/16/16_35.amc"));
}

// A folder of two converters' rigs that share no joint (the Daz rig of 07_01, CMU's of 111_36
// and, under other names, 16_01): the rigs of the most frames are read, the other's files left
// out with a warning, though the other rig has the most frames of any one rig.
TEST(DatabaseLoader, AFoldersFilesOfARigThatCannotJoinTheOthersAreLeftOut) {
  TempFolder folder("other-rigs");
  const std::string daz = test::read_data("bvh/07_01.bvh");
  std::vector<std::string> daz_files;
  for (int copy = 0; copy < 5; ++copy) {
    // Copies but for a digit more in their last value (the same motion would be read once): 5 x
    // 79 frames.
    std::string text = daz;
    while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
    daz_files.push_back(folder.write(fmt::format("07_0{}.bvh", copy), text + std::to_string(copy + 1) + "\n"));
  }
  folder.write("111_36.bvh", test::read_data("bvh/111_36.bvh"));  // 367 frames
  folder.write("16_01.bvh", test::read_data("bvh/16_01.bvh"));    // 322
  DatabaseSettings settings = cmu_settings();
  settings.mirror = DatabaseSettings::Mirroring::kOff;  // its walks turn one way: as read
  DatabaseLoadNotes notes;
  auto db = load_database({folder.path().string()}, settings, &notes);
  ASSERT_TRUE(db) << db.error().to_string();
  ASSERT_EQ(db->clips.size(), 2u);
  EXPECT_EQ(db->clips[0].name, "111_36");
  EXPECT_EQ(db->clips[1].name, "16_01");
  ASSERT_EQ(notes.other_rigs.size(), 1u);
  EXPECT_EQ(notes.other_rigs[0].files, daz_files);
  EXPECT_NE(notes.other_rigs[0].reason.find("they share no joint"), std::string::npos) << notes.other_rigs[0].reason;
  const std::vector<std::string> warnings = load_warnings(notes);
  EXPECT_TRUE(std::any_of(warnings.begin(), warnings.end(), [](const std::string& line) {
    return line.starts_with("5 files left out, their rig cannot be read with the library's");
  })) << fmt::format("{}", fmt::join(warnings, "\n"));
  // 16_01 is read on 111_36's names, as when the folder holds those two alone.
  EXPECT_EQ(db->skeletons[static_cast<size_t>(db->clips[1].skeleton)].joint(0).name, "Hips");

  // A file given itself is read or the library is not: an error, as for files of a manifest.
  auto named = load_database({folder.path().string(), test::data_path("bvh/07_12.bvh")}, cmu_settings());
  ASSERT_FALSE(named);
  EXPECT_NE(named.error().message.find("they share no joint"), std::string::npos) << named.error().message;
  std::string manifest_text;
  for (const char* file : {"07_00.bvh", "111_36.bvh"}) manifest_text += fmt::format("[[clip]]\nfile = \"{}\"\n", file);
  auto manifest = load_database({folder.write("lib.toml", manifest_text)}, cmu_settings());
  ASSERT_FALSE(manifest);
  EXPECT_NE(manifest.error().message.find("they share no joint"), std::string::npos) << manifest.error().message;
}

}  // namespace
}  // namespace mg
