// Which files the clip loader takes, by extension in any case; an FBX file's unit.
#include "motiongraph/motion/clip_loader.h"

#include <cstring>
#include <filesystem>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "motion/ascii_fbx.h"
#include "motion/max_apart.h"
#include "motiongraph/export/gltf_writer.h"
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
TEST(ClipFiles, AnAmcTakesItsFoldersOnlyAsfOrOfSeveralItsSubjects) {
  using Paths = std::vector<std::filesystem::path>;
  EXPECT_EQ(asf_of_amc(Paths{"x/skel.asf"}, "x/walk.amc"), "x/skel.asf");
  EXPECT_EQ(asf_of_amc(Paths{"x/07.asf", "x/16.asf", "x/161.asf"}, "x/16_15.amc"), "x/16.asf");
  EXPECT_EQ(asf_of_amc(Paths{"x/07.asf", "x/16.asf", "x/161.asf"}, "x/161_02.amc"), "x/161.asf");
  EXPECT_EQ(asf_of_amc(Paths{"x/07.asf", "x/16.asf"}, "x/99_01.amc"), std::nullopt);
  EXPECT_EQ(asf_of_amc(Paths{"x/07.asf", "x/16.asf"}, "x/1615.amc"), std::nullopt);
  EXPECT_EQ(asf_of_amc(Paths{}, "x/16_15.amc"), std::nullopt);

  // The loader of an AMC file given alone: the same rule, an error naming the file otherwise.
  const std::filesystem::path folder = std::filesystem::temp_directory_path() / "motiongraph-two-asf";
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder);
  const std::string asf = test::read_data("cmu/16/16.asf");
  ASSERT_TRUE(write_file_atomic((folder / "07.asf").string(), asf));
  ASSERT_TRUE(write_file_atomic((folder / "16.asf").string(), asf));
  const std::string amc = test::read_data("cmu/16/16_35.amc");
  ASSERT_TRUE(write_file_atomic((folder / "16_35.amc").string(), amc));
  ASSERT_TRUE(write_file_atomic((folder / "99_01.amc").string(), amc));
  ClipLoader loader{ClipLoadSettings{}};
  auto clip = loader.load((folder / "16_35.amc").string());
  ASSERT_TRUE(clip) << clip.error().to_string();
  EXPECT_EQ(clip->skeleton_path, (folder / "16.asf").string());
  EXPECT_EQ(clip->clip.motion.frame_count, test::load_data_clip("cmu/16/16_35.amc").motion.frame_count);
  clip = loader.load((folder / "99_01.amc").string());
  ASSERT_FALSE(clip);
  EXPECT_EQ(clip.error().file, (folder / "99_01.amc").string());
  EXPECT_NE(clip.error().message.find("none named as its subject"), std::string::npos) << clip.error().message;
  std::filesystem::remove_all(folder);
}

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

// A .gltf whose buffer is a file beside it (as Blender writes "glTF Separate") reads as the .glb
// holding the same bytes; a buffer that is a folder, or missing, is an error naming it.
TEST(ClipLoader, AGltfReadsItsBufferFromTheFileItNames) {
  Clip walk = test::load_data_clip("cmu/16/16_15.amc");
  auto at30 = resample(walk.motion, 30.0);
  ASSERT_TRUE(at30);
  walk.motion = std::move(*at30);
  auto glb = write_glb(walk.skeleton, walk.motion, "walk");
  ASSERT_TRUE(glb) << glb.error().to_string();
  // A GLB: a 12-byte header, then chunks of (length, type, bytes): the JSON, then the buffer.
  const auto chunk = [&](size_t at) {
    uint32_t length = 0;
    std::memcpy(&length, glb->data() + at, sizeof length);
    return std::string_view(*glb).substr(at + 8, length);
  };
  const std::string_view json_chunk = chunk(12);
  const std::string_view bin_chunk = chunk(12 + 8 + json_chunk.size());
  auto json = nlohmann::json::parse(json_chunk);
  ASSERT_EQ(json["buffers"].size(), 1u);
  json["buffers"][0]["uri"] = "walk.bin";
  const size_t length = json["buffers"][0]["byteLength"].get<size_t>();
  ASSERT_LE(length, bin_chunk.size());

  const std::filesystem::path folder = std::filesystem::temp_directory_path() / "motiongraph-separate-gltf";
  std::filesystem::remove_all(folder);
  ASSERT_TRUE(std::filesystem::create_directories(folder));
  const std::string gltf = (folder / "walk.gltf").string();
  ASSERT_TRUE(write_file_atomic(gltf, json.dump()));
  ASSERT_TRUE(write_file_atomic((folder / "walk.bin").string(), bin_chunk.substr(0, length)));
  auto read = ClipLoader({}).load(gltf);
  ASSERT_TRUE(read) << read.error().to_string();
  EXPECT_EQ(read->format, "gltf");
  EXPECT_EQ(read->clip.motion.frame_count, walk.motion.frame_count);
  EXPECT_LT(test::max_apart(walk, read->clip), 1e-5);

  std::filesystem::remove(folder / "walk.bin");
  auto missing = ClipLoader({}).load(gltf);
  ASSERT_FALSE(missing);
  EXPECT_EQ(missing.error().file, gltf);
  EXPECT_NE(missing.error().message.find("walk.bin"), std::string::npos) << missing.error().message;
  std::filesystem::create_directory(folder / "walk.bin");
  auto folder_buffer = ClipLoader({}).load(gltf);
  ASSERT_FALSE(folder_buffer);
  EXPECT_NE(folder_buffer.error().message.find("is a folder, not a file"), std::string::npos)
      << folder_buffer.error().message;
  std::filesystem::remove_all(folder);
}

}  // namespace
}  // namespace mg
