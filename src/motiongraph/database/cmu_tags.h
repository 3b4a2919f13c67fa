// Motion tags from the CMU motion capture database's own descriptions. The index
// (data/cmu/cmu-mocap-index.tsv, B. Hahne's listing of 2008) has one motion per line:
// "MOTION<TAB>DESCRIPTION<TAB>SUBJECT", e.g. "16_15<TAB>walk<TAB>Subject #16 (run, jump, walk)";
// motion ids are the subject number (two or three digits, zero-padded to two) and the trial
// number (two digits): "01_01", "16_15", "143_42". '#' lines and the lines before the
// MOTION header row are preamble.
//
// Descriptions map to tags by whole words (case-insensitive; split at anything that is not
// a letter and at CamelCase humps, so "run/jog" gives run and jog, "RunStop" gives run and
// stop). A small locomotion-centred vocabulary, one tag per word family:
//
//   walk      walk, walks, walking, walked, march, stride, stroll, wander, sneak, snuck, tiptoe,
//             creep, crept, limp
//   run       run, runs, running, ran, jog, jogs, jogging, jogged, sprint, sprinted
//   jump      jump, jumps, jumping, jumped, hop, hops, hopping, hopped, leap, leaps, leaping, leaped,
//             leapt
//   turn      turn, turns, turning, turned, spin, spins, spinning, spun, pivot, pivoting, pivoted
//   stop      stop, stops, stopping, stopped, halt, halted
//   start     start, starts, starting, started
//   sidestep  sidestep, sidesteps, sidestepping, sidestepped, sideways, sideway, strafe, strafes,
//             strafing, strafed
//   backward  backward, backwards
//   sit       sit, sits, sitting, sat, seated
//   climb     climb, climbs, climbing, climbed
//   dance     dance, dances, dancing, danced, salsa
//
// (and the other forms of march, stroll, wander, sneak, tiptoe, creep and limp in -ing and -ed).
// "veer" gives no tag: CMU uses it for a gradual curve of a walk or run, which stays a walk
// or a run ("run/jog, veer left" -> run; "walk, 90-degree left turn" -> walk, turn).
// "Unknown" and anything outside the vocabulary give no tag. Tags apply to whole clips.
#pragma once

#include <map>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "motiongraph/core/error.h"

namespace mg {

struct CmuMotion {
  std::string motion_id;    // "16_15"
  std::string description;  // "walk, 90-degree left turn"
  std::string subject;      // "Subject #16 (run, jump, walk)"; may be empty
  int line = 0;
};

struct CmuIndex {
  std::vector<CmuMotion> motions;  // in file order
  std::map<std::string, int, std::less<>> by_id;  // motion id -> index into motions

  // The motion of a clip name such as "16_15" (or "16_1", "016_15": subject and trial are
  // read as numbers); nullptr when the name is not a CMU id or the index does not list it.
  const CmuMotion* find(std::string_view clip_name) const;
};

// Parses the TSV index from its text. Rules (errors at their line): each row has a motion id
// and a description separated by a tab (the subject column may be missing); ids are
// "<subject>_<trial>" in digits; no id twice.
Result<CmuIndex> parse_cmu_index(std::string_view tsv_text, std::string file_name);

// The canonical CMU id of a clip name ("16_15" -> "16_15", "1_1" -> "01_01"); nullopt when
// the name is not digits '_' digits.
std::optional<std::string> cmu_motion_id(std::string_view clip_name);

// Tags of a description, in vocabulary order, each at most once.
std::vector<std::string> cmu_description_tags(std::string_view description);

// Tags of a clip's name, read as a description is: a studio's or a user's own library says in
// its file names what each clip holds ("Walk_Forward_01" -> walk, "run-stop" -> run, stop,
// "JumpInPlace" -> jump, "take_07" and "16_15" -> none; database_loader.h: for the clips that
// neither a manifest nor CMU's index tags).
std::vector<std::string> clip_name_tags(std::string_view name);

// The tag names the keyword mapping can produce, in order.
std::span<const std::string_view> cmu_tag_vocabulary();

}  // namespace mg
