// Which files the clip loader takes, by extension in any case; an FBX file's unit.
#include "motiongraph/motion/clip_loader.h"

#include <filesystem>

#include <gtest/gtest.h>

#include "motion/ascii_fbx.h"
#include "motion/max_apart.h"
#include "motiongraph/io/file.h"
#include "motiongraph/motion/length_unit.h"
#include "motiongraph/motion/resample.h"
#include "test_data.h"

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

namespace mg {
namespace {

// An FBX file whose stated unit makes the figure no human size (exported with the wrong one:
// the numbers are centimetres, the file says metres) is read in the unit that does, and says so;
// --scale (metres per unit of the file's numbers) overrides; a file whose unit is right is read in it.
TEST(ClipLoader, AnFbxFilesUnitIsKeptUnlessItMakesNoHumanFigure) {
  Clip walk = test::load_data_clip("cmu/16/16_15.amc");
  auto at30 = resample(walk.motion, 30.0);
  ASSERT_TRUE(at30);
  walk.motion = std::move(*at30);
  const auto written = [&](double unit_scale_factor, const std::string& name) {
    test::AsciiFbxSettings settings;
    settings.unit_scale_factor = unit_scale_factor;
    const std::string path = (std::filesystem::temp_directory_path() / name).string();
    EXPECT_TRUE(write_file_atomic(path, test::ascii_fbx({{"walk", walk}}, settings)));
    return path;
  };
  const std::string right = written(1.0, "motiongraph-unit-cm.fbx");
  // The same numbers (centimetres), said to be metres: a figure 100 times too tall.
  std::string wrong_text = read_text_file(right).value();
  const std::string said = "\"UnitScaleFactor\", \"double\", \"Number\", \"\",1\n";
  ASSERT_NE(wrong_text.find(said), std::string::npos);
  wrong_text.replace(wrong_text.find(said), said.size(), "\"UnitScaleFactor\", \"double\", \"Number\", \"\",100\n");
  const std::string wrong = (std::filesystem::temp_directory_path() / "motiongraph-unit-m.fbx").string();
  ASSERT_TRUE(write_file_atomic(wrong, wrong_text));

  ClipLoader loader({});
  auto kept = loader.load(right);
  ASSERT_TRUE(kept) << kept.error().to_string();
  EXPECT_FALSE(kept->clip.detected_unit);
  EXPECT_DOUBLE_EQ(kept->file_metres_per_unit, 0.01);
  EXPECT_LT(test::max_apart(walk, kept->clip), 1e-5);
  auto settled = loader.load(wrong);
  ASSERT_TRUE(settled) << settled.error().to_string();
  ASSERT_TRUE(settled->clip.detected_unit);
  EXPECT_EQ(settled->clip.detected_unit->unit.name, "cm");
  EXPECT_DOUBLE_EQ(settled->file_metres_per_unit, 1.0);
  EXPECT_LT(test::max_apart(walk, settled->clip), 1e-5);
  ClipLoadSettings given;
  given.bvh_metres_per_unit = 0.02;  // --scale: twice the centimetre
  auto scaled = ClipLoader(given).load(wrong);
  ASSERT_TRUE(scaled);
  EXPECT_FALSE(scaled->clip.detected_unit);
  const double size = figure_size(walk.skeleton, walk.motion);
  EXPECT_NEAR(figure_size(scaled->clip.skeleton, scaled->clip.motion), 2.0 * size, 1e-4);
  std::filesystem::remove(right);
  std::filesystem::remove(wrong);
}

}  // namespace
}  // namespace mg
