#include "motiongraph/core/counted.h"

#include <gtest/gtest.h>

namespace mg {
namespace {

TEST(Counted, OneIsSingularAnyOtherCountPlural) {
  EXPECT_EQ(counted(1, "clip"), "1 clip");
  EXPECT_EQ(counted(0, "clip"), "0 clips");
  EXPECT_EQ(counted(15, "clip"), "15 clips");
  EXPECT_EQ(counted(-1, "metre"), "-1 metres");
  EXPECT_EQ(counted(1, "match", "matches"), "1 match");
  EXPECT_EQ(counted(2, "match", "matches"), "2 matches");
}

}  // namespace
}  // namespace mg
