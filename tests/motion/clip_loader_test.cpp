// Which files the clip loader takes, by extension in any case.
#include "motiongraph/motion/clip_loader.h"

#include <gtest/gtest.h>

namespace mg {
namespace {

TEST(ClipFiles, ClipsGltfAndFbxByExtensionInAnyCase) {
  for (const char* clip : {"a/16_15.amc", "walk.BVH", "set.glb", "Set.GLTF", "mixamo.FBX"}) {
    EXPECT_TRUE(is_clip_file(clip)) << clip;
  }
  for (const char* other : {"16.asf", "lib.toml", "walk.bvh.txt", ".bvh", "README", ""}) {
    EXPECT_FALSE(is_clip_file(other)) << other;
  }
  EXPECT_TRUE(is_gltf_file("x/set.GlB"));
  EXPECT_TRUE(is_gltf_file("scene.gltf"));
  EXPECT_FALSE(is_gltf_file("walk.bvh"));
  EXPECT_FALSE(is_gltf_file("model.glb.bin"));
  EXPECT_TRUE(is_fbx_file("x/Walk.Fbx"));
  EXPECT_FALSE(is_fbx_file("walk.fbx.txt"));
  for (const char* scene : {"set.glb", "a.gltf", "b.fbx"}) EXPECT_TRUE(is_scene_file(scene)) << scene;
  for (const char* other : {"walk.bvh", "16_15.amc", "lib.toml"}) EXPECT_FALSE(is_scene_file(other)) << other;
}

}  // namespace
}  // namespace mg
