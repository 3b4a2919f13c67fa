// Loading a MotionDatabase from files: folders, single clip files and TOML manifests
// (manifest.h, docs/manifest.md). Every clip is read through ClipLoader, cut to its frame
// range when a manifest gives one, and resampled to the database frame rate; clips follow
// one another in global frame order, in input order.
//
// Inputs, each one of:
//   - a folder: its clip files and those of the folders in it (database/folder_tree.h), an AMC
//     with its folder's .asf; other files are ignored;
//   - a .amc file (its skeleton: DatabaseSettings::asf_path, or the only .asf beside it) or a
//     .bvh file;
//   - a .toml manifest.
//
// Skeletons: each distinct skeleton file (an ASF, or a BVH, which holds its own) is one entry
// of db.skeletons. Clips of different skeletons share a database when their joints have the
// same names and the same parents, in the same order (point clouds compare joints by index).
// Skeletons that differ in some joints only (fingers in some files, a prop joint) are all read
// on the joints they share (motion/common_joints.h), in the first skeleton's order, when those
// are at least two thirds of the smallest skeleton's and hold both ankles; the notes name what
// was dropped. Otherwise loading fails, naming both files and the first joint that differs.
//
// Tags: a manifest clip that mentions tags (tags = [...] or ranges) gets exactly those; any
// other clip, when settings.cmu_tags is on, gets the tags of its CMU description
// (cmu_tags.h), looked up by its file's stem ("16_15"; also when a manifest renames the
// clip), and one CMU's index does not list, when settings.name_tags is on, those of the words of
// its name (clip_name_tags: "Walk_Forward_01" -> walk), or where it gives none, of its file's
// stem (a manifest naming it "hero") or, then, of its folder below the folder given
// ("locomotion/run/r01" -> run); for all its
// frames, but walk and run only where its root travels and stop where it halts (travel_tags.h;
// settings.travel_tags), and a clip called both walk and run walk where its pace is a walk's
// and run where it is a run's (pace_spans: a clip, or a part cut at a glitch, of one pace gets
// that one).
//
// Errors: a missing input or clip file, a clip file that cannot be read (but for a folder's,
// which is passed over: DatabaseLoadNotes::unreadable, unless the folder holds no other), a clip
// with fewer than 2 frames after resampling (it holds no motion), a frame range past the end of
// its file, skeletons too unlike to share, more than 64 tags; each names the file (and the
// manifest line when a manifest gave it).
#pragma once

#include <optional>
#include <stop_token>
#include <string>
#include <string_view>
#include <vector>

#include "motiongraph/core/error.h"
#include "motiongraph/core/progress.h"
#include "motiongraph/database/motion_database.h"
#include "motiongraph/database/travel_tags.h"
#include "motiongraph/database/turning_balance.h"
#include "motiongraph/motion/capture_glitches.h"
#include "motiongraph/motion/clip_doubts.h"
#include "motiongraph/motion/clip_loader.h"
#include "motiongraph/motion/in_place_choice.h"
#include "motiongraph/motion/length_unit_choice.h"
#include "motiongraph/motion/loop.h"
#include "motiongraph/motion/rig_matching.h"
#include "motiongraph/motion/up_axis_choice.h"

namespace mg {

struct DatabaseSettings {
  double fps = 30.0;                    // database frame rate; every clip is resampled to it
  bool prefer_manifest_fps = true;      // a manifest's `fps` replaces `fps` (the CLI clears
                                        // this when the user gives --fps)
  // Reading options for clips not given by a manifest (a manifest's own values win for its
  // clips; these are its defaults otherwise).
  std::optional<std::string> asf_path;  // skeleton for AMC files given one by one
  std::optional<double> bvh_metres_per_unit;  // BVH carries no unit; nullopt: chosen per file
                                              // from its figure's size (length_unit.h)
  std::optional<UpAxis> up_axis;        // nullopt: chosen per file from its figure's shape
                                        // (up_axis.h)
  double input_fps = 0.0;               // > 0: the capture rate, overriding the files'
  bool keep_rest_frames = false;        // keep leading rest/T-pose frames of BVH files, the
                                        // frames a capture glitch cuts off clips' ends, and
                                        // clips whole where glitches within them would cut
                                        // them (motion/capture_glitches.h)
  TravelSource travel = TravelSource::kAuto;  // where each clip's travel over the floor comes
                                              // from (motion/in_place.h): kAuto recovers it
                                              // from the feet for clips animated in place
  // The foot joints' names; given, they win over a manifest's [feet]. The loaded database's
  // contacts are found with them (database_contacts.h); a named joint that is missing fails
  // the load.
  FootJointNames foot_names;

  // Tags from CMU's descriptions for clips a manifest gives no tags. The index is
  // cmu_index_text when not empty, else the file at cmu_index_path when not empty (--cmu-index),
  // else, with cmu_index_beside_inputs, a cmu-mocap-index.tsv beside or up to two folders above
  // the first input (a folder, or a file's folder) that has one; with none, the index the
  // project ships, built in (shipped_cmu_index.h).
  bool cmu_tags = true;
  std::string cmu_index_text;
  std::string cmu_index_path;
  bool cmu_index_beside_inputs = true;
  // Tags from the words of clip names (cmu_tags.h clip_name_tags), or of their folders' below the
  // one given, for clips a manifest gives no tags and CMU's index does not list: a studio's
  // "Walk_Forward_01.bvh" walks, and so does its "walk/w01.bvh".
  bool name_tags = true;
  // Walk and run from a description or a name only on the frames where the root travels
  // (min_speed_mps 0: on the whole clip).
  TravelTagSettings travel_tags;

  // Each clip also mirrored left to right (motion/mirror.h), as one more clip after all of them,
  // named NAME_mirrored, with the tags of its own: a library whose walks turn one way turns both.
  // kWhenLopsided mirrors a library whose clips turn one way much more than the other
  // (database/turning_balance.h) and that holds less than max_lopsided_mirror_s of motion (the
  // distance stage has four times the pairs). A skeleton that cannot be mirrored keeps its clips
  // as they are (DatabaseLoadNotes::unmirrored says why).
  enum class Mirroring { kOff, kWhenLopsided, kAlways };
  Mirroring mirror = Mirroring::kWhenLopsided;
  double max_lopsided_mirror_s = 1800.0;

  // Clips that loop (motion/loop.h: a game's cycle, its end meeting its start) go on past their
  // end for loop_overlap_frames frames at the database's rate (0: a third of a second and one,
  // the default window's and one), so a transition's window can lead from the end back to the
  // start.
  bool loops = true;
  int loop_overlap_frames = 0;
  int loop_frames_at(double database_fps) const;

  // A bar on stderr while the files are read, one step a clip file (core/progress.h: drawn on a
  // terminal only): a library of hours takes a minute to read.
  bool progress_bar = false;
  // ... and, given, a line of how far it got every kProgressLineSeconds, terminal or not.
  ProgressLines progress_lines;
  // Asks the reading to stop (core/stop.h): before each clip file, loading fails with
  // stopped_error() once it does.
  std::stop_token stop;

  // The files the command will write (its output, report, exports): loading fails, before any
  // motion is read, on a clip file a folder holds or a manifest names, a manifest, an AMC's
  // skeleton or the CMU index that is one of them (io/file.h check_not_an_output), so that no
  // run writes over a file it read.
  std::vector<std::string> outputs;

  Status validate() const;
};

// "auto", "on" or "off" (--mirror) as DatabaseSettings::Mirroring; nullopt for anything else.
std::optional<DatabaseSettings::Mirroring> parse_mirroring(std::string_view text);
// ... and back.
const char* mirroring_name(DatabaseSettings::Mirroring mirroring);

// Settings that read every clip as `load` does (and find its feet with load.foot_names); the
// rate and the CMU tags at their defaults. `info` on a library reads it so.
DatabaseSettings database_settings_reading_as(const ClipLoadSettings& load);

// What loading chose by itself or noticed, for the caller to report: the unit of each BVH file
// read without one (length_unit.h), in clip order, the up axis of each file read without one,
// the clips whose travel was recovered from their feet (motion/in_place.h), and a line for each
// clip that looks wrong as read (motion/clip_doubts.h: off the floor, feet never planted).
struct DatabaseLoadNotes {
  struct DetectedUnit {
    std::string file;
    LengthUnitChoice choice;
  };
  std::vector<DetectedUnit> detected_units;
  struct DetectedUpAxis {
    std::string file;
    UpAxisChoice choice;                // the file's own
    std::optional<UpAxis> library_axis;  // read in the library's axis instead, its own not settled

    UpAxis axis_read() const { return library_axis.value_or(choice.axis); }
  };
  // Files read without an up axis given, those that follow the library's last.
  std::vector<DetectedUpAxis> detected_up_axes;
  struct RecoveredTravel {
    std::string file;
    TravelSource source;  // kAuto: judged in place; kFeet: asked for
    InPlaceChoice choice;
  };
  std::vector<RecoveredTravel> recovered_travels;  // clips whose travel came from their feet
  // BVH files whose leading rest or T-pose frames (a converter's, motion/rest_frame.h) were
  // dropped, once a file (DatabaseSettings::keep_rest_frames keeps them).
  struct RestFrames {
    std::string file;
    int frames = 0;  // at the file's rate
  };
  std::vector<RestFrames> rest_frames;
  // Files whose first or last frames a capture glitch cut off (motion/glitched_ends.h), once a
  // file.
  struct GlitchedEnds {
    std::string file;
    int leading = 0;  // frames, at the file's rate
    int trailing = 0;
  };
  std::vector<GlitchedEnds> glitched_ends;
  // Clips cut at capture glitches within them (motion/capture_glitches.h), once a clip: the
  // glitches, the parts kept (the first under the clip's name, the others its _part2, _part3...)
  // and the frames in none.
  struct GlitchSplit {
    std::string file;
    std::string clip;  // the clip's name
    std::vector<FileGlitch> glitches;
    struct Part {
      std::string clip;
      int first_frame = 0, last_frame = 0;  // the file's frames, 1-based
    };
    std::vector<Part> parts;
    int dropped_frames = 0;  // at the file's rate
  };
  std::vector<GlitchSplit> glitch_splits;
  // When the skeletons differ in some joints (motion/common_joints.h): the joints every clip
  // was read on, and each skeleton's dropped ones (those of skeletons that lost any).
  std::vector<std::string> common_joints;
  struct DroppedJoints {
    std::string skeleton;
    std::vector<std::string> joints;
  };
  std::vector<DroppedJoints> dropped_joints;
  // Skeletons read from a joint below their root, the library's other rigs' root
  // (motion/common_joints.h reroot_at): a root-motion joint above the hips composed into them.
  struct Rerooted {
    std::string skeleton;
    std::string root;                // the joint they start at now
    std::vector<std::string> above;  // the joints composed into it, their root first
    std::vector<std::string> dropped;  // joints that hung off those, dropped
  };
  std::vector<Rerooted> rerooted;
  // Files whose root travels without turning (an engine's root motion) and had joints beside the
  // body, dropped as the body's joint took the root's travel (motion/trajectory_joint.h): the
  // skeleton is that file's, the root the body's joint, `above` the folded root.
  std::vector<Rerooted> folded_roots;
  // Files whose rig is the first file's under other names or in another rest pose
  // (motion/rig_matching.h), read on the first's names and rest pose.
  struct MatchedRig {
    std::string file;
    std::vector<std::pair<std::string, std::string>> renamed;  // (its name, the library's) where they differ
    std::optional<RestPoseDifference> rest_pose;              // when re-expressed on the first's rest pose
  };
  std::vector<MatchedRig> matched_rigs;
  // Clips found to loop, played on past their end (DatabaseSettings::loops).
  struct Loop {
    std::string clip;
    std::string file;
    LoopChoice choice;
    int added_frames = 0;  // at the database's rate
  };
  std::vector<Loop> loops;
  std::vector<DoubtedClip> clip_doubts;  // in clip order (motion/clip_doubts.h)
  // Clips whose description's walk or run was left off some of their frames (the root stands
  // there: DatabaseSettings::travel_tags), in clip order.
  struct StandingTag {
    std::string clip;
    std::string tag;
    int tagged_frames = 0;  // the frames that travel (a clip called walk and run: at either pace)
    int frames = 0;         // the clip's
  };
  std::vector<StandingTag> standing_tags;
  // Clips tagged by the words of their names (DatabaseSettings::name_tags), in clip order, with
  // the tags the words gave (before the travel rule) and whose words they were.
  struct NameTagged {
    std::string clip;
    std::vector<std::string> tags;
    std::string source;  // "name" (the clip's), "file" (its file's stem, or animation, a manifest
                         // naming it otherwise) or "folder" (below the one given)
    std::string words;   // the name, stem or folder that gave them
  };
  std::vector<NameTagged> name_tagged;
  double standing_speed_mps = 0.0;  // the speed under which they were left off
  // Tags a description gave that no frame keeps (every clip it named stands: CMU 14's "jog" on
  // the spot), with the clips that asked for them: the library has none of them.
  struct VanishedTag {
    std::string tag;
    std::vector<std::string> clips;
  };
  std::vector<VanishedTag> vanished_tags;
  // Files a folder holds whose rig cannot be read with the library's (the rigs that can, of the
  // most frames): the files, in order, and why (the error a library of them all would give).
  struct OtherRigs {
    std::vector<std::string> files;
    std::string reason;
  };
  std::vector<OtherRigs> other_rigs;
  // Files a folder holds that cannot be read (cut short, another format under the extension, a
  // converter's mistake), passed over with the error that reading gave: one bad file in a library
  // of hundreds does not stop it. Given itself, or named by a manifest, such a file is an error.
  std::vector<Error> unreadable;
  // Files a folder holds with a pose rather than a motion (no frame, or under 2 at the library's
  // rate), passed over: the frames in the file and its rate.
  struct Pose {
    std::string file;
    int frames = 0;
    double fps = 0.0;
  };
  std::vector<Pose> poses;
  // Files a folder left out (another file holds a clip of the same name: one take in two
  // formats), and clips renamed because their name was taken, one line each.
  std::vector<std::string> name_clashes;
  // DatabaseSettings::mirror: which way the clips read turn (before any is mirrored), the clips
  // mirrored (their names, NAME_mirrored unless taken, after all the clips read), and the
  // skeletons that could not be, with why.
  TurningBalance turning;
  DatabaseSettings::Mirroring mirroring = DatabaseSettings::Mirroring::kWhenLopsided;  // as asked
  bool mirrored_for_turning = false;  // by kWhenLopsided
  bool too_long_to_mirror = false;    // lopsided, but max_lopsided_mirror_s or more of motion
  double max_lopsided_mirror_s = 0.0;  // DatabaseSettings'
  std::vector<std::string> mirrored;
  std::vector<std::string> mirror_sources;  // per mirrored clip, the clip it mirrors
  struct Unmirrored {
    std::string skeleton;
    std::string reason;
    int clips = 0;
  };
  std::vector<Unmirrored> unmirrored;
};

// The warnings loading gives the user, one line each: files left out and clips renamed for
// their names (a take in two formats, a clip given twice), the files read in the library's up axis
// rather than their own, the joints dropped to read every clip on the same ones, the files read
// as the first file's rig (other names, another rest pose), the tags of descriptions no frame
// keeps (walk or run where every clip stands), then the clips that look wrong as read.
std::vector<std::string> load_warnings(const DatabaseLoadNotes& notes);

Result<MotionDatabase> load_database(const std::vector<std::string>& inputs, const DatabaseSettings& settings,
                                     DatabaseLoadNotes* notes = nullptr);

}  // namespace mg
