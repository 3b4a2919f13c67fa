#include "motiongraph/motion/length_unit.h"

#include <algorithm>
#include <cmath>
#include <string_view>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "motion/static_root_bvh.h"
#include "motiongraph/io/bvh_parser.h"
#include "motiongraph/motion/bvh_import.h"
#include "test_data.h"

namespace mg {
namespace {

TEST(LengthUnit, AHumanHeightInAnyCandidateUnitGivesThatUnit) {
  for (const LengthUnit& unit : length_unit_candidates()) {
    for (double height_m = 1.2; height_m <= 2.2; height_m += 0.05) {
      const LengthUnitChoice choice = choose_length_unit(height_m / unit.metres_per_unit);
      EXPECT_EQ(choice.unit.name, unit.name) << height_m << " m";
      EXPECT_TRUE(choice.plausible);
      EXPECT_NEAR(choice.figure_size_m, height_m, 1e-9);
    }
  }
}

// `also` is the next closest unit to a typical height among those giving a person's size
// (0.9-2.6 m), by brute force over the candidates; none when the choice is the only one.
TEST(LengthUnit, AnotherUnitGivingAPersonsSizeIsNamed) {
  for (double size = 10.0; size <= 3000.0; size *= 1.01) {
    const LengthUnitChoice choice = choose_length_unit(size);
    std::vector<std::pair<double, std::string_view>> plausible;  // (miss, name)
    for (const LengthUnit& unit : length_unit_candidates()) {
      const double m = size * unit.metres_per_unit;
      if (m >= 0.9 && m <= 2.6) plausible.emplace_back(std::abs(std::log(m / 1.7)), unit.name);
    }
    std::sort(plausible.begin(), plausible.end());
    ASSERT_EQ(choice.plausible, !plausible.empty()) << size;
    if (plausible.size() < 2) {
      EXPECT_FALSE(choice.also) << size;
      continue;
    }
    EXPECT_EQ(choice.unit.name, plausible[0].second) << size;
    ASSERT_TRUE(choice.also) << size;
    EXPECT_EQ(choice.also->name, plausible[1].second) << size;
    EXPECT_NEAR(choice.also_figure_size_m, size * choice.also->metres_per_unit, 1e-12) << size;
  }
  // The child of 0.95 m in centimetres: read in inches, with centimetres named.
  const LengthUnitChoice child = choose_length_unit(95.0);
  EXPECT_EQ(child.unit.name, "inch");
  ASSERT_TRUE(child.also);
  EXPECT_EQ(child.also->name, "cm");
  EXPECT_NEAR(child.also_figure_size_m, 0.95, 1e-12);
}

TEST(LengthUnit, ASizeNoUnitMakesHumanIsReadInMetresAndFlagged) {
  for (double size : {0.0, -1.0, 10.0, 5000.0, 1e7, std::nan("")}) {
    const LengthUnitChoice choice = choose_length_unit(size);
    EXPECT_FALSE(choice.plausible) << size;
    EXPECT_EQ(choice.unit.metres_per_unit, 1.0) << size;
  }
}

TEST(LengthUnit, EveryBundledBvhGetsTheUnitItsSourceDocuments) {
  // data/README.md: CMU conversions keep the ASF unit (1/0.45 inch); subject 7's are in cm.
  const std::pair<const char*, const char*> expected[] = {{"bvh/16_01.bvh", "CMU unit (1/0.45 inch)"},
                                                          {"bvh/131_01.bvh", "CMU unit (1/0.45 inch)"},
                                                          {"bvh/111_36.bvh", "CMU unit (1/0.45 inch)"},
                                                          {"bvh/07_01.bvh", "cm"},
                                                          {"bvh/07_12.bvh", "cm"}};
  for (const auto& [file, unit] : expected) {
    const Clip clip = test::load_data_clip(file);
    ASSERT_TRUE(clip.detected_unit) << file;
    EXPECT_EQ(clip.detected_unit->unit.name, unit) << file;
    EXPECT_TRUE(clip.detected_unit->plausible) << file;
    EXPECT_GT(clip.detected_unit->figure_size_m, 1.2) << file;
    EXPECT_LT(clip.detected_unit->figure_size_m, 2.0) << file;
  }
  // A given scale is used as it is, with no detection.
  const Clip given = test::load_data_clip("bvh/07_01.bvh", 0.056444);
  EXPECT_FALSE(given.detected_unit);
}

TEST(LengthUnit, TheSizeScalesWithTheLengthsAndSurvivesATPose) {
  const Clip clip = test::load_data_clip("cmu/16/16_15.amc");
  const double size = figure_size(clip.skeleton, clip.motion);
  EXPECT_GT(size, 1.4);
  EXPECT_LT(size, 2.0);
  Clip scaled = clip;
  scale_lengths(scaled, 39.37);
  EXPECT_NEAR(figure_size(scaled.skeleton, scaled.motion), 39.37 * size, 1e-9 * size);
  // All rotations zero (the rest pose, arms out for this skeleton): still a human size.
  Clip rest = clip;
  for (Quat& q : rest.motion.local_rotations) q = Quat::Identity();
  const double rest_size = figure_size(rest.skeleton, rest.motion);
  EXPECT_GT(rest_size, 1.4);
  EXPECT_LT(rest_size, 2.2);
  // A skeleton without frames is its rest pose: the same size (a BVH of a skeleton alone).
  Clip none = clip;
  none.motion = clip.motion.slice(0, 0);
  EXPECT_NEAR(figure_size(none.skeleton, none.motion), rest_size, 1e-9);
  scale_lengths(none, 100.0);
  EXPECT_EQ(choose_length_unit(figure_size(none.skeleton, none.motion)).unit.name, "cm");
}

TEST(LengthUnit, AStaticRootFileInMillimetresOrInchesIsReadInThem) {
  const Clip plain = test::load_data_clip("cmu/16/16_35.amc");
  for (const auto& [units_per_metre, name] : {std::pair{1000.0, "mm"}, std::pair{1.0 / 0.0254, "inch"}}) {
    auto doc = parse_bvh(test::static_root_bvh(plain, Vec3::Zero(), Quat::Identity(), units_per_metre), "u.bvh");
    ASSERT_TRUE(doc);
    auto clip = clip_from_bvh(*doc, {});
    ASSERT_TRUE(clip);
    ASSERT_TRUE(clip->detected_unit);
    EXPECT_EQ(clip->detected_unit->unit.name, name);
    EXPECT_LT(test::max_position_error_by_name(plain, *clip), 1e-4);
  }
}

TEST(LengthUnit, AFigureOfNoHumanSizeIsFlagged) {
  // The walk in cm, shrunk tenfold: 17 units tall is 17 m, 17 cm, 43 cm or 96 cm (CMU unit,
  // within the range), so shrink it a hundredfold instead: 1.7 units fits nothing.
  const Clip plain = test::load_data_clip("cmu/16/16_15.amc");
  auto doc = parse_bvh(test::static_root_bvh(plain, Vec3::Zero(), Quat::Identity(), 1.0), "tiny.bvh");
  ASSERT_TRUE(doc);
  auto metres = clip_from_bvh(*doc, {});
  ASSERT_TRUE(metres && metres->detected_unit);
  EXPECT_TRUE(metres->detected_unit->plausible);
  EXPECT_EQ(metres->detected_unit->unit.name, "m");
  auto tiny_doc = parse_bvh(test::static_root_bvh(plain, Vec3::Zero(), Quat::Identity(), 0.1), "tiny.bvh");
  ASSERT_TRUE(tiny_doc);
  auto tiny = clip_from_bvh(*tiny_doc, {});
  ASSERT_TRUE(tiny && tiny->detected_unit);
  EXPECT_FALSE(tiny->detected_unit->plausible);
}

}  // namespace
}  // namespace mg
