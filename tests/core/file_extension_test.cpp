#include "motiongraph/core/file_extension.h"

#include <gtest/gtest.h>

namespace mg {
namespace {

TEST(LowerExtension, LowersTheLastComponentsExtensionOnly) {
  EXPECT_EQ(lower_extension("walk.bvh"), ".bvh");
  EXPECT_EQ(lower_extension("WALK.BVH"), ".bvh");
  EXPECT_EQ(lower_extension("Out/Clip.GlB"), ".glb");
  EXPECT_EQ(lower_extension("MOCAP.D/16_01.AMC"), ".amc");
  EXPECT_EQ(lower_extension("a.tar.XZ"), ".xz");
  EXPECT_EQ(lower_extension("Graph.MGRAPH"), ".mgraph");
}

TEST(LowerExtension, EmptyWithoutOne) {
  EXPECT_EQ(lower_extension("README"), "");
  EXPECT_EQ(lower_extension("clips.d/"), "");
  EXPECT_EQ(lower_extension(".hidden"), "");
  EXPECT_EQ(lower_extension(""), "");
}

}  // namespace
}  // namespace mg
