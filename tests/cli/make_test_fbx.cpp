// make_test_fbx [--up AXIS] [--unit FACTOR] OUT.fbx AMC...: writes the clips (AMC with the .asf
// beside them), resampled to 30 fps, as one ASCII FBX built by FBX's rules (tests/motion/ascii_fbx.h:
// joints resting in frames of their own, PreRotations, every rotation order, an armature turned
// and scaled, a skinned mesh and an animated prop), an animation stack each named as its file
// ("Armature|16_15", as Blender names them); --up: the file's up axis (+y, +z, -z, +x, ...); --unit: FBX's UnitScaleFactor
// (centimetres times it; 2.54: inches). For cli_fbx_test.sh.
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <string>

#include "motion/ascii_fbx.h"
#include "motiongraph/io/file.h"
#include "motiongraph/motion/clip_loader.h"
#include "motiongraph/motion/resample.h"

int main(int argc, char** argv) {
  mg::test::AsciiFbxSettings settings;
  settings.skin = true;
  settings.stack_prefix = "Armature|";
  settings.armature_rotation = mg::Quat(Eigen::AngleAxisd(0.5, mg::Vec3::UnitY()));
  settings.armature_scale = 0.5;
  int first = 1;
  for (; first < argc && std::string(argv[first]).starts_with("--"); ++first) {
    const std::string flag = argv[first];
    if (flag == "--up" && first + 1 < argc) {
      settings.up = argv[++first];
    } else if (flag == "--unit" && first + 1 < argc) {
      settings.unit_scale_factor = std::atof(argv[++first]);
    } else {
      first = argc;  // unknown: usage
    }
  }
  if (argc < first + 2 || !(settings.unit_scale_factor > 0.0)) {
    std::fprintf(stderr, "usage: make_test_fbx [--up AXIS] [--unit FACTOR] OUT.fbx AMC...\n");
    return 2;
  }
  mg::ClipLoadSettings load;
  load.travel = mg::TravelSource::kRoot;  // the capture as CMU gives it
  mg::ClipLoader loader(load);
  std::vector<std::pair<std::string, mg::Clip>> clips;
  for (int i = first + 1; i < argc; ++i) {
    auto loaded = loader.load(argv[i]);
    if (!loaded) {
      std::fprintf(stderr, "make_test_fbx: %s\n", loaded.error().to_string().c_str());
      return 1;
    }
    auto resampled = mg::resample(loaded->clip.motion, 30.0);
    if (!resampled) {
      std::fprintf(stderr, "make_test_fbx: %s\n", resampled.error().to_string().c_str());
      return 1;
    }
    loaded->clip.motion = std::move(*resampled);
    clips.emplace_back(std::filesystem::path(argv[i]).stem().string(), std::move(loaded->clip));
  }
  try {
    if (auto s = mg::write_file_atomic(argv[first], mg::test::ascii_fbx(clips, settings)); !s) {
      std::fprintf(stderr, "make_test_fbx: %s\n", s.error().to_string().c_str());
      return 1;
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "make_test_fbx: %s\n", e.what());
    return 1;
  }
  return 0;
}
