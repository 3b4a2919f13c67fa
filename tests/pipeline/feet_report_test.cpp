// How info tells the feet and their contacts: the share of frames each foot is planted, and a
// clip of one frame, whose contacts are not measured, said so (not "planted 0 %").
#include "motiongraph/pipeline/feet_report.h"

#include <gtest/gtest.h>

#include <vector>

#include "motiongraph/skeleton/foot_joints.h"
#include "test_data.h"

namespace mg {
namespace {

TEST(FeetReport, SharesOfFramesPlantedAndOneFrameUnmeasured) {
  const Clip clip = test::load_data_clip("cmu/16/16_15.amc");
  const auto feet = find_foot_joints(clip.skeleton);
  ASSERT_TRUE(feet) << feet.error().to_string();
  const auto left = static_cast<ContactMask>(contact_bit(FootSide::kLeft, FootPart::kToe));
  const auto right = static_cast<ContactMask>(contact_bit(FootSide::kRight, FootPart::kAnkle));
  const std::vector<ContactMask> four{left, left, static_cast<ContactMask>(left | right), 0};
  EXPECT_EQ(feet_description(clip.skeleton, *feet, four, "found by name"),
            "lfoot > ltoes, rfoot > rtoes (found by name; planted 75 % and 25 % of frames)");
  const nlohmann::json json = feet_json(clip.skeleton, *feet, four, "found by name");
  EXPECT_DOUBLE_EQ(json["left"]["planted_share"].get<double>(), 0.75);
  EXPECT_DOUBLE_EQ(json["right"]["planted_share"].get<double>(), 0.25);
  const std::vector<ContactMask> one{left};
  EXPECT_EQ(feet_description(clip.skeleton, *feet, one, "found by name"),
            "lfoot > ltoes, rfoot > rtoes (found by name; one frame: contacts not measured)");
  const nlohmann::json single = feet_json(clip.skeleton, *feet, one, "found by name");
  EXPECT_TRUE(single["left"]["planted_share"].is_null());
  EXPECT_TRUE(single["right"]["planted_share"].is_null());
}

}  // namespace
}  // namespace mg
