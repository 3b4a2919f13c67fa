#include "motiongraph/motion/acclaim_import.h"

#include <numbers>

#include <gtest/gtest.h>

#include "motiongraph/motion/forward_kinematics.h"
#include "test_data.h"

namespace mg {
namespace {

constexpr double kMetresPerUnit = 0.0254 / 0.45;

std::string mini_asf(const std::string& a_axis, const std::string& a_dofs, double length_unit = 0.45) {
  return ":units\n  length " + std::to_string(length_unit) +
         "\n  angle deg\n:root\n  order TX TY TZ RX RY RZ\n  axis XYZ\n  position 0 0 0\n  orientation 0 0 0\n"
         ":bonedata\n"
         "  begin\n    id 1\n    name a\n    direction 0 0 1\n    length 1\n    axis " + a_axis + "\n    dof " + a_dofs + "\n  end\n"
         "  begin\n    id 2\n    name b\n    direction 0 0 1\n    length 1\n    axis 0 0 0 XYZ\n  end\n"
         ":hierarchy\n  begin\n    root a\n    a b\n  end\n";
}

struct Built {
  AcclaimRig rig;
  Motion motion;
  std::vector<Vec3> positions;  // world positions of frame 0
};

Built build(const std::string& asf_text, const std::string& amc_text) {
  auto asf = parse_asf(asf_text, "t.asf");
  EXPECT_TRUE(asf) << asf.error().to_string();
  auto rig = build_acclaim_rig(*asf);
  EXPECT_TRUE(rig) << rig.error().to_string();
  auto amc = parse_amc(amc_text, "t.amc", rig->amc_layout, true);
  EXPECT_TRUE(amc) << amc.error().to_string();
  Built built{*rig, motion_from_amc(*rig, *amc, 120.0), {}};
  built.positions = world_positions(built.rig.skeleton, built.motion);
  return built;
}

TEST(AcclaimImport, JointsAreRootBonesThenEnds) {
  auto built = build(mini_asf("0 0 0 XYZ", "rx"), "1\nroot 0 0 0 0 0 0\na 0\n");
  const Skeleton& s = built.rig.skeleton;
  ASSERT_EQ(s.joint_count(), 4);
  EXPECT_EQ(s.joint(0).name, "root");
  EXPECT_EQ(s.joint(1).name, "a");
  EXPECT_EQ(s.joint(2).name, "b");
  EXPECT_EQ(s.joint(3).name, "b_end");
  EXPECT_TRUE(s.joint(3).end_site);
  EXPECT_EQ(s.joint(2).parent, 1);
  // b starts where a ends: one unit along z.
  EXPECT_TRUE(built.positions[2].isApprox(Vec3(0, 0, kMetresPerUnit), 1e-12));
  EXPECT_TRUE(built.positions[3].isApprox(Vec3(0, 0, 2 * kMetresPerUnit), 1e-12));
}

TEST(AcclaimImport, DofRotationIsTakenInTheBoneAxisFrame) {
  // C = Rz(90): the bone's local x axis is the world y axis, so "rx 90" turns the bone about
  // world y, carrying its direction +z onto +x (L = C M C^-1).
  auto built = build(mini_asf("0 0 90 XYZ", "rx"), "1\nroot 0 0 0 0 0 0\na 90\n");
  EXPECT_TRUE(built.positions[2].isApprox(Vec3(kMetresPerUnit, 0, 0), 1e-12)) << built.positions[2].transpose();
  EXPECT_TRUE(built.positions[3].isApprox(Vec3(2 * kMetresPerUnit, 0, 0), 1e-12)) << built.positions[3].transpose();
}

TEST(AcclaimImport, DofsApplyInTheOrderListed) {
  // "dof rz rx" with 90, 90: first rz (z stays z), then rx: +z -> -y. With the opposite order
  // (rx first: +z -> -y, then rz: -y -> +x) the bone would end along +x instead.
  auto built = build(mini_asf("0 0 0 XYZ", "rz rx"), "1\nroot 0 0 0 0 0 0\na 90 90\n");
  EXPECT_TRUE(built.positions[2].isApprox(Vec3(0, -kMetresPerUnit, 0), 1e-12)) << built.positions[2].transpose();
  auto swapped = build(mini_asf("0 0 0 XYZ", "rx rz"), "1\nroot 0 0 0 0 0 0\na 90 90\n");
  EXPECT_TRUE(swapped.positions[2].isApprox(Vec3(kMetresPerUnit, 0, 0), 1e-12)) << swapped.positions[2].transpose();
}

TEST(AcclaimImport, RootTranslationAndUnits) {
  auto built = build(mini_asf("0 0 0 XYZ", "rx"), "1\nroot 10 20 30 0 0 0\na 0\n");
  EXPECT_TRUE(built.positions[0].isApprox(Vec3(10, 20, 30) * kMetresPerUnit, 1e-12));
  // Halving the unit length doubles every position (length 0.9 -> 1 unit = 0.0254/0.9 m).
  auto scaled = build(mini_asf("0 0 0 XYZ", "rx", 0.9), "1\nroot 10 20 30 0 0 0\na 0\n");
  for (size_t j = 0; j < built.positions.size(); ++j) {
    EXPECT_TRUE(scaled.positions[j].isApprox(built.positions[j] / 2, 1e-12));
  }
}

TEST(AcclaimImport, RadiansAreHonoured) {
  auto degrees = build(mini_asf("0 0 90 XYZ", "rx"), ":DEGREES\n1\nroot 0 0 0 0 0 0\na 30\n");
  auto radians = build(mini_asf("0 0 90 XYZ", "rx"),
                       ":RADIANS\n1\nroot 0 0 0 0 0 0\na " + std::to_string(std::numbers::pi / 6) + "\n");
  EXPECT_LT(test::max_position_error(degrees.positions, radians.positions), 1e-7);
}

TEST(AcclaimImport, BundledSkeletonIsInMetres) {
  Clip clip = test::load_data_clip("cmu/16/16_15.amc");
  EXPECT_EQ(clip.skeleton.joint_count(), 31 + 7);
  for (int j = 1; j < clip.skeleton.joint_count(); ++j) EXPECT_LT(clip.skeleton.parent(j), j);
  // A standing adult: feet near the floor, head about 1.6-1.9 m up.
  const auto positions = world_positions(clip.skeleton, clip.motion);
  const int head = *clip.skeleton.find("head");
  const int toes = *clip.skeleton.find("ltoes");
  EXPECT_GT(positions[head].y() - positions[toes].y(), 1.3);
  EXPECT_LT(positions[head].y() - positions[toes].y(), 1.9);
}

TEST(AcclaimImport, AgreesWithAnIndependentBvhConversionOfTheSameCapture) {
  // 16_01.bvh (amc2bvh) holds the same values as 16_01.amc; its README says the hip, spine to
  // thorax and legs are faithful (the converter misplaces children of multi-child bones).
  Clip amc = test::load_data_clip("cmu/16/16_01.amc");
  Clip bvh = test::load_data_clip("bvh/16_01.bvh", kMetresPerUnit, 120.0);
  ASSERT_EQ(amc.motion.frame_count, bvh.motion.frame_count);
  const auto pa = world_positions(amc.skeleton, amc.motion);
  const auto pb = world_positions(bvh.skeleton, bvh.motion);
  const std::vector<std::string> faithful = {"lhipjoint", "lfemur", "ltibia", "lfoot", "ltoes", "rhipjoint", "rfemur",
                                             "rtibia", "rfoot", "rtoes", "lowerback", "upperback", "thorax"};
  int compared = 0;
  for (const auto& name : faithful) {
    const int ja = *amc.skeleton.find(name);
    const int jb = *bvh.skeleton.find(name);
    for (int f = 0; f < amc.motion.frame_count; ++f) {
      const double error = (pa[f * amc.skeleton.joint_count() + ja] - pb[f * bvh.skeleton.joint_count() + jb]).norm();
      ASSERT_LT(error, 2e-5) << name << " frame " << f;  // the BVH has 4 decimals
      ++compared;
    }
  }
  const double root_error = (pa[0] - pb[0]).norm();
  EXPECT_LT(root_error, 2e-5);
  EXPECT_EQ(compared, 13 * 322);
}

TEST(AcclaimImport, OneCleanErrorPerHierarchyRule) {
  const std::string base = mini_asf("0 0 0 XYZ", "rx");
  auto with = [&](const std::string& from, const std::string& to) { return test::replace_once(base, from, to); };
  const std::vector<test::ErrorCase> cases = {
      {"unknown child", with("    a b\n", "    a b x\n"), 28, "unknown bone 'x'"},
      {"unknown parent", with("    a b\n", "    x b\n"), 28, "unknown bone 'x'"},
      {"two parents", with("    a b\n", "    a b\n    root b\n"), 29, "second parent"},
      {"own parent", with("    a b\n", "    a a b\n"), 28, "its own parent"},
      {"cycle", with("    root a\n    a b\n", "    a b\n    b a\n"), 28, "cycle"},
      {"unreachable", with("    a b\n", ""), 18, "not reachable"},
      {"duplicate name", with("name b", "name a"), 18, "used twice"},
      {"bone called root", with("name b", "name root"), 18, "may not be called 'root'"},
      {"stretch dof", with("dof rx", "dof rx l"), 10, "not supported"},
      {"zero direction", with("direction 0 0 1\n    length 1\n    axis 0 0 0 XYZ\n  end",
                              "direction 0 0 0\n    length 1\n    axis 0 0 0 XYZ\n  end"), 18, "zero direction"},
  };
  for (const auto& c : cases) {
    auto asf = parse_asf(c.text, "bad.asf");
    std::optional<Error> error;
    if (!asf) {
      error = asf.error();
    } else if (auto rig = build_acclaim_rig(*asf); !rig) {
      error = rig.error();
    }
    ASSERT_TRUE(error) << c.rule;
    test::expect_error_matches(*error, c);
  }
}

}  // namespace
}  // namespace mg
