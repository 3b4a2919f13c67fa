// A database manifest: a TOML file naming the clips of a motion database, with per-clip
// reading options (skeleton, BVH scale, capture rate), an optional frame range, and motion
// tags for the whole clip or for frame ranges of it. Format for users: docs/manifest.md.
//
// Frame numbers count the file's frames from 1: frame 1 is the first frame stored in the file
// (for CMU's AMC files, numbered from 1, the number written before it; an AMC numbered from
// elsewhere is counted by position too), counted before any rest frame a BVH reader drops.
// Ranges are inclusive at both ends. Paths are kept as written; the loader
// resolves them against the manifest's folder (database_loader.h).
//
// parse_manifest reads text only (it never touches the disk). Every error names the manifest
// and the line: TOML syntax, unknown keys (typos), wrong value types, and the rules below.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "motiongraph/core/error.h"
#include "motiongraph/motion/in_place_choice.h"
#include "motiongraph/motion/up_axis_choice.h"
#include "motiongraph/skeleton/foot_joints.h"

namespace mg {

// Tags on frames [first_frame, last_frame] of a clip (file numbering, inclusive).
struct ManifestRange {
  int first_frame = 1;
  int last_frame = 1;
  std::vector<std::string> tags;
  int line = 0;  // of the range's table, for later messages
};

struct ManifestClip {
  std::string file;                        // as written: relative to the manifest's folder
  std::optional<std::string> name;         // clip name; the file's stem when absent (CMU
                                           // tags are looked up by the stem either way)
  std::optional<std::string> skeleton;     // ASF for an AMC clip (overrides the default)
  std::optional<std::string> animation;    // of a glTF or FBX clip (default: its first)
  std::optional<double> bvh_scale;         // metres per BVH unit (overrides the default)
  std::optional<UpAxis> up_axis;           // the clip's up axis (overrides the default)
  std::optional<TravelSource> travel;      // where its travel comes from (overrides the default)
  std::optional<double> input_fps;         // capture rate, overriding the file's
  std::optional<bool> keep_rest_frames;    // a BVH converter's leading rest frames, and glitched ends, kept
  std::optional<int> first_frame;          // file numbering, from 1; absent: the first
  std::optional<int> last_frame;           // inclusive; absent: the last
  std::optional<std::vector<std::string>> tags;  // absent: no whole-clip tags given
  std::vector<ManifestRange> ranges;

  // Lines in the manifest, for messages about this clip found later (missing file, a frame
  // range past the end of the file).
  int line = 0;
  int file_line = 0;
  int skeleton_line = 0;
  int frames_line = 0;  // of last_frame, or of first_frame when only it is given
  int animation_line = 0;

  // True when the manifest says anything about tags for this clip (even `tags = []`):
  // then the manifest alone decides its tags and no CMU index lookup is made.
  bool gives_tags() const { return tags.has_value() || !ranges.empty(); }
};

struct Manifest {
  std::string file_name;
  std::optional<double> fps;               // database frame rate
  std::optional<std::string> skeleton;     // default ASF for AMC clips
  std::optional<double> bvh_scale;         // default metres per BVH unit
  std::optional<UpAxis> up_axis;           // default up axis
  std::optional<TravelSource> travel;      // default travel source (motion/in_place.h)
  std::optional<double> input_fps;         // default capture rate
  std::optional<bool> keep_rest_frames;    // default for the clips (dropped by default)
  std::vector<ManifestClip> clips;
  // [feet]: the foot joints' names (left_ankle, left_toe, right_ankle, right_toe; any may be
  // left out to find that joint by name).
  std::optional<FootJointNames> feet;

  int fps_line = 0;
  int feet_line = 0;
  int skeleton_line = 0;
};

// Parses a manifest from its text. `file_name` is used in messages only.
//
// Rules (each an error at its line): valid TOML; only known keys; values of the right type
// (numbers may be written as integers or floats, frames are integers, tags strings); fps,
// bvh_scale and input_fps positive; up_axis "y" or "z"; travel "auto", "root" or "feet"; at
// least one [[clip]]; each clip has a non-empty `file` ending in .amc or .bvh; `skeleton` only
// on AMC clips and `bvh_scale` only on BVH clips; `keep_rest_frames` a boolean;
// first_frame >= 1, last_frame >= first_frame; each range has first_frame and last_frame,
// first >= 1, last >= first, inside the clip's own frame range when the manifest gives it,
// and at least one tag; tag names non-empty, of letters, digits, '_' and '-'; [feet] names
// non-empty strings, not the same joint twice.
Result<Manifest> parse_manifest(std::string_view toml_text, std::string file_name);

// A tag name as the manifest and the database accept it: non-empty, [A-Za-z0-9_-] only.
bool is_valid_tag_name(std::string_view name);

}  // namespace mg
