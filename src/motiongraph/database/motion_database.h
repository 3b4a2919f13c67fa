// The motion database: every frame of every clip at one frame rate, as one sequence of global
// frame indices (clip after clip), with the clip ranges, the skeletons (one per subject; clips
// of different subjects must share a joint topology) and motion tags per frame range.
// Everything downstream (point clouds, distances, the graph) indexes frames globally. The
// feet's contacts of every frame are found once, when the database is loaded
// (database_contacts.h), and travel with it in the graph file.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "motiongraph/core/huge_pages.h"
#include "motiongraph/motion/foot_contacts.h"
#include "motiongraph/motion/motion.h"

namespace mg {

struct DatabaseClip {
  std::string name;          // e.g. "16_15"
  std::string source;        // the file it was read from, as given
  int skeleton = 0;          // index into MotionDatabase::skeletons
  int first_frame = 0;       // global index of its first frame
  int frame_count = 0;
  Motion motion;             // at the database's fps
  double read_fps = 0.0;     // the rate its file was read at (its own, or --input-fps); 0: not known
};

// A tag on a range of global frames [first_frame, first_frame + frame_count).
struct TagRange {
  int tag = 0;               // index into MotionDatabase::tag_names
  int first_frame = 0;
  int frame_count = 0;
};

// Tag sets as bit masks: bit t set = tag_names[t]. At most 64 tags.
using TagMask = std::uint64_t;

struct MotionDatabase {
  // The block the clips' motion lives in when a graph file was read (one block for hundreds of
  // clips: core/huge_pages.h), or null. Declared first, so that it outlives the clips; a copy
  // of the database copies its motion into ordinary memory.
  std::shared_ptr<HugePageArena> motion_memory;
  double fps = 30.0;
  std::vector<Skeleton> skeletons;
  std::vector<std::string> skeleton_names;  // e.g. the ASF file each came from
  std::vector<DatabaseClip> clips;
  std::vector<std::string> tag_names;
  std::vector<TagRange> tag_ranges;
  // The foot joints' names as the user gave them (manifest [feet], build --feet); empty: found
  // by name (skeleton/foot_joints.h).
  FootJointNames foot_names;
  // Per global frame, the contacts of its clip's feet (motion/foot_contacts.h). Empty when not
  // found yet, or when some skeleton's feet cannot be found: contacts_error then says why.
  std::vector<ContactMask> frame_contacts;
  std::string contacts_error;

  int frame_count() const { return clips.empty() ? 0 : clips.back().first_frame + clips.back().frame_count; }
  // Clip holding a global frame (binary search).
  int clip_of(int frame) const;
  // Tags of every frame (frame_count entries).
  std::vector<TagMask> frame_tags() const;
  // Index of a tag name, adding it when new; -1 when the 64 tags are used up.
  int tag_index(const std::string& name);
  // Names of the tags in a mask, in tag order.
  std::vector<std::string> tag_names_of(TagMask mask) const;
};

}  // namespace mg
