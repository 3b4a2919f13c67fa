// Access to the bundled data (data/) for tests, and small builders shared by them.
#pragma once

#include <optional>
#include <string>

#include "motiongraph/core/error.h"
#include "motiongraph/database/motion_database.h"
#include "motiongraph/graph/transition.h"
#include "motiongraph/motion/bvh_import.h"
#include "motiongraph/motion/motion.h"

namespace mg::test {

// Full path of a file under data/, e.g. data_path("cmu/16/16.asf").
std::string data_path(const std::string& relative);
// Its text; fails the test (throws) if it cannot be read.
std::string read_data(const std::string& relative);

// Loads a bundled clip through the real loader (AMC finds 16.asf beside it).
// A BVH without bvh_metres_per_unit is read in the unit its figure's size gives.
Clip load_data_clip(const std::string& relative, std::optional<double> bvh_metres_per_unit = std::nullopt,
                    double input_fps = 0.0);
// The same with every frame of the file: rest frames and glitched ends kept (--keep-rest-frames).
Clip load_whole_data_clip(const std::string& relative);

// A BVH file's text read as the loader reads it (parse_bvh, then clip_from_bvh with
// `settings`); fails the test (throws) when it cannot be read.
Clip import_bvh(const std::string& text, const BvhImportSettings& settings = {});

// `text` with the first occurrence of `from` replaced by `to`; fails the test if absent.
std::string replace_once(std::string text, const std::string& from, const std::string& to);

// One failing-input case: a rule, the text that breaks it, and the error expected.
struct ErrorCase {
  const char* rule;
  std::string text;
  int line;                  // expected error line
  const char* message_part;  // expected part of the message
};

// Checks an error against a case (non-fatal gtest expectations naming the rule).
void expect_error_matches(const Error& error, const ErrorCase& expected);

// Clips of the bundled data at `fps`, back to back on the first clip's skeleton; optionally
// with a copy of the first clip turned by `yaw` about the vertical and moved by `shift`.
MotionDatabase small_database(const std::vector<std::string>& files, bool add_moved_copy = false, double yaw = 0.0,
                              Vec3 shift = Vec3::Zero(), double fps = 30.0);

// One clip (131_01's BVH) read as two subjects, the second `scale` times larger (a larger
// unit), back to back, with the transition that leaves the first at frame `from` and arrives
// in the second at the same frames over a window of `window` (to_frame = n + from + window -
// 1), its floor alignment the shift of the root between the two scales: played on the first
// subject's skeleton, the walk across it is the first clip itself.
struct ScaledPair {
  Clip small;
  Clip large;
  MotionDatabase db;
  Transition transition;
};
ScaledPair scaled_pair(double scale, int from, int window);

// Largest distance (metres) between two frames x joints position arrays of the same shape.
double max_position_error(const std::vector<Vec3>& a, const std::vector<Vec3>& b);

// Largest distance (metres) between the world positions of the joints of `a` and the joints of
// `b` with the same names, over all frames; fails the test when a joint of `a` has no match or
// the frame counts differ.
double max_position_error_by_name(const Clip& a, const Clip& b);

// The clip with a three-joint finger hung from each wrist (lwrist, rwrist: CMU's names),
// appended after its joints so that theirs keep their indices, turning a little every frame: a
// rig exported with fingers.
Clip with_fingers(const Clip& clip);

// Frame `first` of a clip whose root is its only joint with translation, held still for
// `frames` frames: a pose that never travels.
Clip held_pose(const Clip& clip, int first, int frames);

}  // namespace mg::test
