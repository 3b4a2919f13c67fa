#include "motiongraph/database/cmu_tags.h"

#include <algorithm>

#include <gtest/gtest.h>

#include "test_data.h"

namespace mg {
namespace {

using Tags = std::vector<std::string>;

TEST(CmuTags, DescriptionsToTags) {
  EXPECT_EQ(cmu_description_tags("walk"), Tags{"walk"});
  EXPECT_EQ(cmu_description_tags("run/jog, veer left"), Tags{"run"});
  EXPECT_EQ(cmu_description_tags("walk, 90-degree left turn"), (Tags{"walk", "turn"}));
  EXPECT_EQ(cmu_description_tags("run/jog, sudden stop"), (Tags{"run", "stop"}));
  EXPECT_EQ(cmu_description_tags("slow walk, stop"), (Tags{"walk", "stop"}));
  EXPECT_EQ(cmu_description_tags("forward jump"), Tags{"jump"});
  EXPECT_EQ(cmu_description_tags("playground - forward jumps, turn around"), (Tags{"jump", "turn"}));
  EXPECT_EQ(cmu_description_tags("hop on left foot"), Tags{"jump"});
  EXPECT_EQ(cmu_description_tags("Walking"), Tags{"walk"});
  // CamelCase names of some sessions.
  EXPECT_EQ(cmu_description_tags("RunStop"), (Tags{"run", "stop"}));
  EXPECT_EQ(cmu_description_tags("StartRun"), (Tags{"run", "start"}));
  EXPECT_EQ(cmu_description_tags("JumpForward"), Tags{"jump"});
  EXPECT_EQ(cmu_description_tags("navigate - walk forward, backward, sideways"),
            (Tags{"walk", "sidestep", "backward"}));
  EXPECT_EQ(cmu_description_tags("climb, sit, dangle legs, jump down"), (Tags{"jump", "sit", "climb"}));
  EXPECT_EQ(cmu_description_tags("salsa dance"), Tags{"dance"});
  // Whole words only; no tag for what the vocabulary does not know.
  EXPECT_EQ(cmu_description_tags("navigate busy sidewalk"), Tags{});
  EXPECT_EQ(cmu_description_tags("hopscotch"), Tags{});
  EXPECT_EQ(cmu_description_tags("return"), Tags{});
  EXPECT_EQ(cmu_description_tags("Unknown"), Tags{});
  EXPECT_EQ(cmu_description_tags(""), Tags{});
}

// A studio's or a user's file names say what their clips hold, in words of any case, joined by
// anything, CamelCase or not; names of digits (CMU's own, takes) and words outside the
// vocabulary say nothing.
TEST(CmuTags, ClipNamesToTags) {
  EXPECT_EQ(clip_name_tags("Walk_Forward_01"), Tags{"walk"});
  EXPECT_EQ(clip_name_tags("WALK_FWD"), Tags{"walk"});
  EXPECT_EQ(clip_name_tags("walk-turn-left"), (Tags{"walk", "turn"}));
  EXPECT_EQ(clip_name_tags("run-stop"), (Tags{"run", "stop"}));
  EXPECT_EQ(clip_name_tags("RunLoop"), Tags{"run"});
  EXPECT_EQ(clip_name_tags("jog02"), Tags{"run"});
  EXPECT_EQ(clip_name_tags("JumpInPlace"), Tags{"jump"});
  EXPECT_EQ(clip_name_tags("locomotion/Sprint_Fwd"), Tags{"run"});
  EXPECT_EQ(clip_name_tags("Strafe_Left"), Tags{"sidestep"});
  EXPECT_EQ(clip_name_tags("actor2/walk"), Tags{"walk"});
  EXPECT_EQ(clip_name_tags("take_07"), Tags{});
  EXPECT_EQ(clip_name_tags("16_15"), Tags{});
  EXPECT_EQ(clip_name_tags("Idle"), Tags{});
  EXPECT_EQ(clip_name_tags("walkforward"), Tags{});  // one word the vocabulary does not hold
  EXPECT_EQ(clip_name_tags("return_to_start"), Tags{"start"});
  // Past tenses, as takes are often named after the fact.
  EXPECT_EQ(clip_name_tags("Walked_In"), Tags{"walk"});
  EXPECT_EQ(clip_name_tags("ran_and_stopped"), (Tags{"run", "stop"}));
  EXPECT_EQ(clip_name_tags("JumpedOverGap"), Tags{"jump"});
  EXPECT_EQ(clip_name_tags("strafed-left"), Tags{"sidestep"});
}

TEST(CmuTags, VocabularyIsWhatDescriptionsGive) {
  const auto vocabulary = cmu_tag_vocabulary();
  EXPECT_EQ(vocabulary.size(), 11u);
  for (std::string_view tag : vocabulary) {
    // Each tag's own name is one of its words.
    EXPECT_EQ(cmu_description_tags(tag), Tags{std::string(tag)}) << tag;
  }
}

TEST(CmuTags, MotionIds) {
  EXPECT_EQ(cmu_motion_id("16_15"), "16_15");
  EXPECT_EQ(cmu_motion_id("01_01"), "01_01");
  EXPECT_EQ(cmu_motion_id("1_1"), "01_01");
  EXPECT_EQ(cmu_motion_id("143_42"), "143_42");
  EXPECT_EQ(cmu_motion_id("016_15"), "16_15");
  EXPECT_FALSE(cmu_motion_id("16-15"));
  EXPECT_FALSE(cmu_motion_id("walk"));
  EXPECT_FALSE(cmu_motion_id("16_15_walk"));
  EXPECT_FALSE(cmu_motion_id("_15"));
  EXPECT_FALSE(cmu_motion_id("16_"));
}

TEST(CmuTags, ReadsTheRealIndex) {
  auto index = parse_cmu_index(test::read_data("cmu/cmu-mocap-index.tsv"), "cmu-mocap-index.tsv");
  ASSERT_TRUE(index) << index.error().to_string();
  EXPECT_EQ(index->motions.size(), 2435u);
  EXPECT_EQ(index->motions.front().motion_id, "01_01");
  EXPECT_EQ(index->motions.front().line, 10);  // after the preamble and the header row
  EXPECT_EQ(index->motions.back().motion_id, "144_34");

  const CmuMotion* walk = index->find("16_15");
  ASSERT_NE(walk, nullptr);
  EXPECT_EQ(walk->description, "walk");
  EXPECT_EQ(walk->subject, "Subject #16 (run, jump, walk)");
  ASSERT_NE(index->find("1_1"), nullptr);
  EXPECT_EQ(index->find("1_1")->motion_id, "01_01");
  EXPECT_EQ(index->find("16_99"), nullptr);
  EXPECT_EQ(index->find("walk"), nullptr);
  // Padding in a description is trimmed.
  ASSERT_NE(index->find("78_06"), nullptr);
  EXPECT_EQ(index->find("78_06")->description, "RunningStraight       CleanedGRS");
  EXPECT_EQ(cmu_description_tags(index->find("78_06")->description), Tags{"run"});
}

TEST(CmuTags, BundledClipsGetTheirTags) {
  auto index = parse_cmu_index(test::read_data("cmu/cmu-mocap-index.tsv"), "cmu-mocap-index.tsv");
  ASSERT_TRUE(index) << index.error().to_string();
  const std::vector<std::pair<const char*, Tags>> expected = {
      {"16_01", {"jump"}},          {"16_05", {"jump"}},          {"16_11", {"walk"}},
      {"16_13", {"walk"}},          {"16_15", {"walk"}},          {"16_16", {"walk"}},
      {"16_17", {"walk", "turn"}},  {"16_19", {"walk", "turn"}},  {"16_33", {"walk", "stop"}},
      {"16_35", {"run"}},           {"16_37", {"run"}},           {"16_39", {"run"}},
      {"16_41", {"run", "turn"}},   {"16_43", {"run", "turn"}},   {"16_57", {"run", "stop"}},
  };
  for (const auto& [clip, tags] : expected) {
    const CmuMotion* motion = index->find(clip);
    ASSERT_NE(motion, nullptr) << clip;
    EXPECT_EQ(cmu_description_tags(motion->description), tags) << clip << ": " << motion->description;
  }
}

TEST(CmuTags, IndexWithoutHeaderOrSubjects) {
  auto index = parse_cmu_index("# comment\n16_15\twalk\n\n16_35\trun/jog\tSubject #16\r\n", "mini.tsv");
  ASSERT_TRUE(index) << index.error().to_string();
  ASSERT_EQ(index->motions.size(), 2u);
  EXPECT_EQ(index->motions[0].subject, "");
  EXPECT_EQ(index->motions[1].subject, "Subject #16");
  EXPECT_EQ(index->motions[1].line, 4);
}

TEST(CmuTags, OneCleanErrorPerRule) {
  const std::string base = "preamble line\nMOTION\tDESCRIPTION\tSUBJECT\n16_15\twalk\tS16\n16_35\trun/jog\tS16\n";
  const std::vector<test::ErrorCase> cases = {
      {"no tab", test::replace_once(base, "16_35\trun/jog\tS16", "16_35 run/jog"), 4, "found no tab"},
      {"too many columns", test::replace_once(base, "\tS16\n16_35", "\tS16\textra\n16_35"), 3, "4 columns"},
      {"id not subject_trial", test::replace_once(base, "16_35\t", "16-35\t"), 4, "not of the form"},
      {"id not canonical", test::replace_once(base, "16_35\t", "16_5\t"), 4, "not of the form"},
      {"id twice", test::replace_once(base, "16_35\t", "16_15\t"), 4, "listed twice (first on line 3)"},
  };
  for (const auto& c : cases) {
    auto index = parse_cmu_index(c.text, "bad.tsv");
    ASSERT_FALSE(index) << c.rule;
    EXPECT_EQ(index.error().file, "bad.tsv");
    test::expect_error_matches(index.error(), c);
  }
}

}  // namespace
}  // namespace mg
