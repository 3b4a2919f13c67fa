#include "motiongraph/database/motion_database.h"

#include <gtest/gtest.h>

namespace mg {
namespace {

TEST(MotionDatabase, TagIndicesAndNamesOfMasks) {
  MotionDatabase db;
  EXPECT_EQ(db.tag_index("walk"), 0);
  EXPECT_EQ(db.tag_index("run"), 1);
  EXPECT_EQ(db.tag_index("walk"), 0);  // known names keep their index
  EXPECT_EQ(db.tag_index("jump"), 2);
  EXPECT_TRUE(db.tag_names_of(0).empty());
  EXPECT_EQ(db.tag_names_of(TagMask{1} << 1), std::vector<std::string>({"run"}));
  EXPECT_EQ(db.tag_names_of((TagMask{1} << 2) | 1), std::vector<std::string>({"walk", "jump"}));
  EXPECT_EQ(db.tag_names_of(TagMask{1} << 40), std::vector<std::string>());  // no such tag
  for (int t = 3; t < 64; ++t) EXPECT_EQ(db.tag_index("tag" + std::to_string(t)), t);
  EXPECT_EQ(db.tag_index("one too many"), -1);
  EXPECT_EQ(db.tag_names_of(~TagMask{0}).size(), 64u);
}

}  // namespace
}  // namespace mg
