#include "motiongraph/skeleton/foot_joints.h"

#include <gtest/gtest.h>

#include "motiongraph/motion/forward_kinematics.h"
#include "test_data.h"

namespace mg {
namespace {

// A leg chain per side below a root: hip -> knee -> each name in `left` (resp. `right`) in
// turn, the last optionally followed by an End Site (named <parent>_end as the importers do).
Skeleton legs(const std::vector<std::string>& left, const std::vector<std::string>& right, bool end_sites = false) {
  std::vector<JointDef> joints;
  joints.push_back(JointDef{.name = "Hips", .parent = -1, .animated_translation = true});
  auto chain = [&](const std::string& prefix, const std::vector<std::string>& names, double x) {
    joints.push_back(JointDef{.name = prefix + "Hip", .parent = 0, .rest_offset_m = Vec3(x, -0.1, 0.0)});
    joints.push_back(JointDef{.name = prefix + "Knee", .parent = static_cast<int>(joints.size()) - 1,
                              .rest_offset_m = Vec3(0.0, -0.4, 0.0)});
    for (const std::string& name : names) {
      joints.push_back(JointDef{.name = name, .parent = static_cast<int>(joints.size()) - 1,
                                .rest_offset_m = Vec3(0.0, -0.4, 0.02)});
    }
    if (end_sites) {
      joints.push_back(JointDef{.name = names.back() + "_end", .parent = static_cast<int>(joints.size()) - 1,
                                .rest_offset_m = Vec3(0.0, -0.05, 0.12), .end_site = true});
    }
  };
  chain("L", left, 0.1);
  chain("R", right, -0.1);
  return Skeleton(std::move(joints));
}

struct Named {
  std::string left_ankle, left_toe, right_ankle, right_toe;  // "" for no toe
};

Named names_of(const Skeleton& skeleton, const FootJoints& feet) {
  auto name = [&](int j) { return j < 0 ? std::string() : skeleton.joint(j).name; };
  return {name(feet.left.ankle), name(feet.left.toe), name(feet.right.ankle), name(feet.right.toe)};
}

void expect_feet(const Skeleton& skeleton, const Named& expected, const std::string& rig,
                 const FootJointNames& names = {}) {
  auto feet = find_foot_joints(skeleton, names);
  ASSERT_TRUE(feet) << rig << ": " << feet.error().to_string();
  const Named found = names_of(skeleton, *feet);
  EXPECT_EQ(found.left_ankle, expected.left_ankle) << rig;
  EXPECT_EQ(found.left_toe, expected.left_toe) << rig;
  EXPECT_EQ(found.right_ankle, expected.right_ankle) << rig;
  EXPECT_EQ(found.right_toe, expected.right_toe) << rig;
}

TEST(FootJoints, TheBundledFilesFeetAreFoundByName) {
  // Names read from the files themselves (data/README.md lists the converters).
  struct Case {
    const char* file;
    Named expected;
  };
  const Case cases[] = {
      {"cmu/16/16_15.amc", {"lfoot", "ltoes", "rfoot", "rtoes"}},           // CMU ASF
      {"bvh/16_01.bvh", {"lfoot", "ltoes", "rfoot", "rtoes"}},              // CMU names in BVH
      {"bvh/111_36.bvh", {"LeftFoot", "LeftToeBase", "RightFoot", "RightToeBase"}},  // MotionBuilder
      {"bvh/131_01.bvh", {"LeftAnkle", "LeftToe", "RightAnkle", "RightToe"}},         // 3dsMax-friendly
      {"bvh/07_01.bvh", {"lFoot", "lFoot_end", "rFoot", "rFoot_end"}},      // Daz: no toe, an End Site
  };
  for (const Case& c : cases) {
    const Clip clip = test::load_data_clip(c.file);
    expect_feet(clip.skeleton, c.expected, c.file);
  }
}

TEST(FootJoints, OnTheBundledClipsEachToeIsLowerThanItsAnkleAndTheSidesAreApart) {
  // The joints found are feet: over a clip the toe is lower than the ankle on average, and
  // the two ankles are further apart than a foot's length only when they are different feet.
  for (const char* file : {"cmu/16/16_15.amc", "bvh/16_01.bvh", "bvh/111_36.bvh", "bvh/131_01.bvh", "bvh/07_01.bvh"}) {
    const Clip clip = test::load_data_clip(file);
    auto feet = find_foot_joints(clip.skeleton);
    ASSERT_TRUE(feet) << file;
    const auto positions = world_positions(clip.skeleton, clip.motion);
    const size_t joints = static_cast<size_t>(clip.skeleton.joint_count());
    for (const Foot& foot : {feet->left, feet->right}) {
      ASSERT_GE(foot.toe, 0) << file;
      double ankle_height = 0.0, toe_height = 0.0, length = 0.0;
      for (int f = 0; f < clip.motion.frame_count; ++f) {
        ankle_height += positions[f * joints + foot.ankle].y();
        toe_height += positions[f * joints + foot.toe].y();
        length += (positions[f * joints + foot.ankle] - positions[f * joints + foot.toe]).norm();
      }
      const double frames = clip.motion.frame_count;
      EXPECT_LT(toe_height / frames, ankle_height / frames - 0.02) << file;
      EXPECT_GT(length / frames, 0.05) << file;  // a foot, not a marker on the ankle
      EXPECT_LT(length / frames, 0.35) << file;
    }
  }
}

TEST(FootJoints, CommonRigsNamingsAreFound) {
  struct Case {
    const char* rig;
    std::vector<std::string> left, right;
    Named expected;
  };
  const Case cases[] = {
      {"Mixamo",
       {"mixamorig:LeftFoot", "mixamorig:LeftToeBase", "mixamorig:LeftToe_End"},
       {"mixamorig:RightFoot", "mixamorig:RightToeBase", "mixamorig:RightToe_End"},
       {"mixamorig:LeftFoot", "mixamorig:LeftToeBase", "mixamorig:RightFoot", "mixamorig:RightToeBase"}},
      {"Mixamo, another namespace",
       {"mixamorig1:LeftFoot", "mixamorig1:LeftToeBase"},
       {"mixamorig1:RightFoot", "mixamorig1:RightToeBase"},
       {"mixamorig1:LeftFoot", "mixamorig1:LeftToeBase", "mixamorig1:RightFoot", "mixamorig1:RightToeBase"}},
      {"3ds Max Biped",
       {"Bip01 L Foot", "Bip01 L Toe0"},
       {"Bip01 R Foot", "Bip01 R Toe0"},
       {"Bip01 L Foot", "Bip01 L Toe0", "Bip01 R Foot", "Bip01 R Toe0"}},
      {"Unreal", {"foot_l", "ball_l"}, {"foot_r", "ball_r"}, {"foot_l", "ball_l", "foot_r", "ball_r"}},
      {"Blender rigify", {"DEF-foot.L", "DEF-toe.L"}, {"DEF-foot.R", "DEF-toe.R"},
       {"DEF-foot.L", "DEF-toe.L", "DEF-foot.R", "DEF-toe.R"}},
      {"Bandai Namco", {"Foot_L", "Toes_L"}, {"Foot_R", "Toes_R"}, {"Foot_L", "Toes_L", "Foot_R", "Toes_R"}},
      {"HumanIK", {"Character1_LeftFoot", "Character1_LeftToeBase"},
       {"Character1_RightFoot", "Character1_RightToeBase"},
       {"Character1_LeftFoot", "Character1_LeftToeBase", "Character1_RightFoot", "Character1_RightToeBase"}},
      {"LAFAN1", {"LeftFoot", "LeftToe"}, {"RightFoot", "RightToe"}, {"LeftFoot", "LeftToe", "RightFoot", "RightToe"}},
      // SMPL and Kinect have both an ankle and a "foot": the foot is the toe.
      {"SMPL", {"left_ankle", "left_foot"}, {"right_ankle", "right_foot"},
       {"left_ankle", "left_foot", "right_ankle", "right_foot"}},
      {"Kinect", {"AnkleLeft", "FootLeft"}, {"AnkleRight", "FootRight"},
       {"AnkleLeft", "FootLeft", "AnkleRight", "FootRight"}},
      {"upper case", {"LFOOT", "LTOES"}, {"RFOOT", "RTOES"}, {"LFOOT", "LTOES", "RFOOT", "RTOES"}},
  };
  for (const Case& c : cases) expect_feet(legs(c.left, c.right), c.expected, c.rig);
}

TEST(FootJoints, AnAnkleWithoutAToeUsesItsEndSiteOrStandsAlone) {
  // An unnamed only child (a toe joint, or an End Site) stands for the toe.
  expect_feet(legs({"LeftFoot", "LeftForefoot"}, {"RightFoot", "RightForefoot"}),
              {"LeftFoot", "LeftForefoot", "RightFoot", "RightForefoot"}, "unnamed toe joint");
  expect_feet(legs({"LeftFoot"}, {"RightFoot"}, true), {"LeftFoot", "LeftFoot_end", "RightFoot", "RightFoot_end"},
              "end sites");
  // A leaf ankle: the ankle alone.
  expect_feet(legs({"LeftFoot"}, {"RightFoot"}), {"LeftFoot", "", "RightFoot", ""}, "leaf ankle");
  // Two children, neither named a toe: no way to choose, the ankle alone.
  const Skeleton base = legs({"LeftFoot"}, {"RightFoot"});
  std::vector<JointDef> joints(base.joints().begin(), base.joints().end());
  const int left_ankle = *base.find("LeftFoot");
  joints.push_back(JointDef{.name = "LeftHeel", .parent = left_ankle, .rest_offset_m = Vec3(0.0, -0.05, -0.05)});
  joints.push_back(JointDef{.name = "LeftTip", .parent = left_ankle, .rest_offset_m = Vec3(0.0, -0.05, 0.12)});
  expect_feet(Skeleton(joints), {"LeftFoot", "", "RightFoot", ""}, "two unnamed children");
}

TEST(FootJoints, TheNearestToeBelowTheAnkleIsTaken) {
  // A toe base with a toe below it: the base. A toe-named joint elsewhere is not taken.
  expect_feet(legs({"LeftFoot", "LeftToeBase", "LeftToe"}, {"RightFoot", "RightToeBase", "RightToe"}),
              {"LeftFoot", "LeftToeBase", "RightFoot", "RightToeBase"}, "toe base then toe");
  const Skeleton base = legs({"LeftFoot"}, {"RightFoot"});
  std::vector<JointDef> joints(base.joints().begin(), base.joints().end());
  joints.push_back(JointDef{.name = "LeftToe", .parent = 0, .rest_offset_m = Vec3(0.1, -0.9, 0.1)});
  expect_feet(Skeleton(joints), {"LeftFoot", "", "RightFoot", ""}, "a toe not below the ankle");
}

TEST(FootJoints, NamesAreFoldedAsDocumented) {
  EXPECT_EQ(folded_joint_name("mixamorig:Left_Foot"), "leftfoot");
  EXPECT_EQ(folded_joint_name("Armature|mixamorig_LeftToeBase"), "lefttoebase");
  EXPECT_EQ(folded_joint_name("Bip001 R Toe0"), "rtoe0");
  EXPECT_EQ(folded_joint_name("DEF-foot.L"), "footl");
  EXPECT_EQ(folded_joint_name("Character12_LeftFoot"), "leftfoot");
  // A name that is only a prefix keeps it.
  EXPECT_EQ(folded_joint_name("Bip01"), "bip01");
  EXPECT_EQ(folded_joint_name("def"), "def");
}

TEST(FootJoints, NoAnkleIsAnErrorNamingWhatWasLookedFor) {
  const Skeleton skeleton = legs({"LeftShin2"}, {"RightFoot", "RightToeBase"});
  auto feet = find_foot_joints(skeleton);
  ASSERT_FALSE(feet);
  const std::string& message = feet.error().message;
  EXPECT_NE(message.find("no left ankle joint"), std::string::npos) << message;
  for (const char* name : {"leftankle", "lankle", "anklel", "leftfoot", "lfoot", "footl"}) {
    EXPECT_NE(message.find(name), std::string::npos) << name << ": " << message;
  }
  // A right foot missing says right.
  auto right = find_foot_joints(legs({"LeftFoot"}, {"RightShin2"}));
  ASSERT_FALSE(right);
  EXPECT_NE(right.error().message.find("no right ankle joint"), std::string::npos) << right.error().message;
}

TEST(FootJoints, ExplicitNamesWinAndIgnoreCase) {
  const Skeleton skeleton = legs({"LAnk", "LFront"}, {"RAnk", "RFront"});
  EXPECT_FALSE(find_foot_joints(skeleton));  // nothing to find by the rules
  FootJointNames names{"lank", "LFRONT", "RAnk", "rfront"};
  expect_feet(skeleton, {"LAnk", "LFront", "RAnk", "RFront"}, "explicit", names);
  // An explicit ankle with the toe found below it (its only child here).
  expect_feet(skeleton, {"LAnk", "LFront", "RAnk", "RFront"}, "explicit ankles", FootJointNames{"LAnk", "", "RAnk", ""});
  // Explicit names override what the rules would find.
  const Skeleton cmu = legs({"lfoot", "ltoes"}, {"rfoot", "rtoes"});
  expect_feet(cmu, {"LKnee", "lfoot", "rfoot", "rtoes"}, "override", FootJointNames{"LKnee", "lfoot", "", ""});
}

TEST(FootJoints, EachRuleForNamesGivesItsError) {
  const Skeleton skeleton = legs({"LeftFoot", "LeftToe"}, {"RightFoot", "RightToe"});
  struct Case {
    const char* rule;
    FootJointNames names;
    const char* message_part;
  };
  const Case cases[] = {
      {"same ankle both sides", {"LeftFoot", "", "leftfoot", ""}, "left and right ankles are both named"},
      {"same toe both sides", {"", "LeftToe", "", "LEFTTOE"}, "left and right toes are both named"},
      {"left toe is its ankle", {"LeftFoot", "LeftFoot", "", ""}, "left toe and ankle are both named"},
      {"right toe is its ankle", {"", "", "RightFoot", "rightfoot"}, "right toe and ankle are both named"},
      {"missing ankle", {"LeftAnkle", "", "", ""}, "no joint named 'LeftAnkle' (given as the left ankle)"},
      {"missing toe", {"", "", "", "RightToes"}, "no joint named 'RightToes' (given as the right toe)"},
      {"toe not below its ankle", {"", "RightToe", "", ""}, "the left toe 'RightToe' is not below the left ankle"},
      {"the ankles are one joint", {"", "", "LeftFoot", ""}, "the same joint 'LeftFoot'"},
  };
  for (const Case& c : cases) {
    auto feet = find_foot_joints(skeleton, c.names);
    ASSERT_FALSE(feet) << c.rule;
    EXPECT_NE(feet.error().message.find(c.message_part), std::string::npos) << c.rule << ": " << feet.error().message;
  }
}

TEST(FootJointNames, ParsedFromFourCommaSeparatedNamesAnyEmpty) {
  auto all = parse_foot_joint_names("LeftAnkle,LeftToe,RightAnkle,RightToe");
  ASSERT_TRUE(all) << all.error().to_string();
  EXPECT_EQ(*all, (FootJointNames{"LeftAnkle", "LeftToe", "RightAnkle", "RightToe"}));
  auto some = parse_foot_joint_names(" lFoot ,, rFoot,");
  ASSERT_TRUE(some) << some.error().to_string();
  EXPECT_EQ(*some, (FootJointNames{"lFoot", "", "rFoot", ""}));
  auto none = parse_foot_joint_names(",,,");
  ASSERT_TRUE(none);
  EXPECT_TRUE(none->empty());
  for (const char* bad : {"", "LeftAnkle", "a,b,c", "a,b,c,d,e"}) {
    auto parsed = parse_foot_joint_names(bad);
    ASSERT_FALSE(parsed) << bad;
    EXPECT_NE(parsed.error().message.find("four comma-separated"), std::string::npos) << parsed.error().message;
  }
  auto same = parse_foot_joint_names("Foot,,foot,");
  ASSERT_FALSE(same);
  EXPECT_NE(same.error().message.find("both named"), std::string::npos) << same.error().message;
}

}  // namespace
}  // namespace mg
