// make_static_root_bvh [--z-up] [--in-place] [--lying] [--loop FIRST:PERIOD] [--translation-root] OUT_DIR AMC...:
// writes each clip (AMC with
// the .asf beside it) as OUT_DIR/<stem>.bvh in a Bandai-like rig (tests/motion/static_root_bvh.h):
// a static root at the origin above the hips, 6 channels per joint, centimetres; with --z-up,
// every position turned as a z-up tool holds it (+y to +z); with --in-place, the hips' travel
// over the floor taken out (x and z), as "in place" exports do; with --lying, the figure tipped
// to lie along z (a crawl, say) before any turn, its rest pose standing; with --loop, resampled to
// 30 fps and cut to one cycle of PERIOD frames from FIRST made a loop (tests/motion/cycle_loop.h),
// as a game's walk or run cycle is; with --translation-root, instead an engine's root motion
// carrying the translation alone (tests/motion/static_root_bvh.h translation_root_clip: a root
// that travels without turning, an IK helper hanging off it), in metres. For
// cli_static_root_test.sh.
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>

#include "motion/cycle_loop.h"
#include "motion/static_root_bvh.h"
#include "motiongraph/export/bvh_writer.h"
#include "motiongraph/io/file.h"
#include "motiongraph/motion/clip_loader.h"
#include "motiongraph/motion/resample.h"
#include "motiongraph/motion/up_axis.h"

int main(int argc, char** argv) {
  bool z_up = false, in_place = false, lying = false, translation_root = false;
  int loop_first = -1, loop_period = 0;
  int first = 1;
  for (; first < argc && std::string(argv[first]).starts_with("--"); ++first) {
    const std::string flag = argv[first];
    if (flag == "--z-up") {
      z_up = true;
    } else if (flag == "--in-place") {
      in_place = true;
    } else if (flag == "--lying") {
      lying = true;
    } else if (flag == "--translation-root") {
      translation_root = true;
    } else if (flag == "--loop" && first + 1 < argc &&
               std::sscanf(argv[first + 1], "%d:%d", &loop_first, &loop_period) == 2) {
      ++first;
    } else {
      first = argc;  // unknown: usage
    }
  }
  if (argc < first + 2) {
    std::fprintf(stderr, "usage: make_static_root_bvh [--z-up] [--in-place] [--lying] [--loop FIRST:PERIOD] "
                         "[--translation-root] OUT_DIR AMC...\n");
    return 2;
  }
  mg::ClipLoadSettings load;
  load.travel = mg::TravelSource::kRoot;  // the capture as CMU gives it
  mg::ClipLoader loader(load);
  for (int i = first + 1; i < argc; ++i) {
    auto loaded = loader.load(argv[i]);
    mg::Status written = mg::Ok{};
    if (loaded && loop_period > 0) {
      auto resampled = mg::resample(loaded->clip.motion, 30.0);
      if (!resampled) {
        std::fprintf(stderr, "make_static_root_bvh: %s\n", resampled.error().to_string().c_str());
        return 1;
      }
      loaded->clip.motion = std::move(*resampled);
      try {
        loaded->clip = mg::test::loop_of(loaded->clip, loop_first, loop_period, false);
      } catch (const std::exception& e) {
        std::fprintf(stderr, "make_static_root_bvh: %s: %s\n", argv[i], e.what());
        return 1;
      }
    }
    if (loaded) {
      if (in_place) {
        mg::Motion& motion = loaded->clip.motion;
        const int slot = loaded->clip.skeleton.translation_slot(0);
        for (int f = 0; f < motion.frame_count; ++f) {
          mg::Vec3& t = motion.translations(f)[slot];
          t.x() = t.z() = 0.0;
        }
      }
      if (lying) {  // the hips turned +y to +z, with their path
        const mg::Quat tip = mg::up_axis_to_y(mg::UpAxis::kZ).conjugate();
        mg::Motion& motion = loaded->clip.motion;
        const int slot = loaded->clip.skeleton.translation_slot(0);
        for (int f = 0; f < motion.frame_count; ++f) {
          motion.rotations(f)[0] = tip * motion.rotations(f)[0];
          motion.translations(f)[slot] = tip * motion.translations(f)[slot];
        }
      }
      if (z_up) mg::turn_clip(loaded->clip, mg::up_axis_to_y(mg::UpAxis::kZ).conjugate());
      const auto out = std::filesystem::path(argv[first]) / (std::filesystem::path(argv[i]).stem().string() + ".bvh");
      if (translation_root) {
        const mg::Clip engine = mg::test::translation_root_clip(loaded->clip, mg::Quat::Identity(), 0.0, true);
        written = mg::write_file_atomic(out.string(), mg::write_bvh(engine.skeleton, engine.motion, mg::BvhWriteSettings{}));
      } else {
        written = mg::write_file_atomic(out.string(), mg::test::static_root_bvh(loaded->clip));
      }
    }
    if (!loaded || !written) {
      std::fprintf(stderr, "%s\n", (loaded ? written.error() : loaded.error()).to_string().c_str());
      return 1;
    }
  }
  return 0;
}
