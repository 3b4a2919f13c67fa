// Which files the clip loader takes, by extension in any case.
#include "motiongraph/motion/clip_loader.h"

#include <gtest/gtest.h>

namespace mg {
namespace {

TEST(ClipFiles, ClipsAndGltfByExtensionInAnyCase) {
  for (const char* clip : {"a/16_15.amc", "walk.BVH", "set.glb", "Set.GLTF"}) EXPECT_TRUE(is_clip_file(clip)) << clip;
  for (const char* other : {"16.asf", "lib.toml", "walk.bvh.txt", ".bvh", "README", ""}) {
    EXPECT_FALSE(is_clip_file(other)) << other;
  }
  EXPECT_TRUE(is_gltf_file("x/set.GlB"));
  EXPECT_TRUE(is_gltf_file("scene.gltf"));
  EXPECT_FALSE(is_gltf_file("walk.bvh"));
  EXPECT_FALSE(is_gltf_file("model.glb.bin"));
}

}  // namespace
}  // namespace mg
