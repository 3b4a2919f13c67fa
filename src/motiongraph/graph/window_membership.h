// Which motion classes a candidate transition belongs to: those every frame of both its windows
// (the k frames it leaves, the k it arrives in) carry. Worked out once per frame for a call that
// looks at many candidates (transition selection, bridges), so that each candidate costs two
// lookups.
#pragma once

#include <span>
#include <vector>

#include "motiongraph/database/motion_database.h"
#include "motiongraph/graph/transition.h"

namespace mg {

// Per frame: the tags of `tags` that every frame of the window leaving it (arriving at it)
// carries, and whether every one of those frames is of the untagged class; 0 / false where the
// window leaves the data. A candidate belongs to a tag when both its windows carry it, and to the
// untagged class (tag -1) when both windows are of it.
struct WindowMembership {
  std::vector<TagMask> leave, arrive;
  std::vector<char> leave_none, arrive_none;

  bool inside(const Transition& c) const {
    const int frames = static_cast<int>(leave.size());
    return c.from_frame >= 0 && c.from_frame < frames && c.to_frame >= 0 && c.to_frame < frames;
  }
  TagMask tags_of(const Transition& c) const {
    return inside(c) ? leave[static_cast<size_t>(c.from_frame)] & arrive[static_cast<size_t>(c.to_frame)] : 0;
  }
  bool untagged(const Transition& c) const {
    return inside(c) && leave_none[static_cast<size_t>(c.from_frame)] && arrive_none[static_cast<size_t>(c.to_frame)];
  }
  bool belongs(const Transition& c, int tag) const { return tag >= 0 ? (tags_of(c) >> tag & 1) != 0 : untagged(c); }
};

// The frames of the untagged class: those of clips no frame of which carries one of `tags` (the
// connected tags). A clip of a type elsewhere belongs to its type alone: its frames of no type are
// its way in and out (the steps where a walk's root stands, which walk is left off:
// database/travel_tags.h), joined to the graph through windows mixed with the type's. As a class
// of their own they held the complete CMU subject 16, where they are 2 % of the frames, at the
// automatic threshold's ceiling for every type (docs/performance.md).
std::vector<char> untagged_class_frames(const MotionDatabase& db, TagMask tags);

// For frames tagged `frame_tags` and windows of `window` frames; `untagged_class` one entry per
// frame (untagged_class_frames), or empty: every frame that carries none of `tags`.
WindowMembership window_membership(std::span<const TagMask> frame_tags, TagMask tags, int window,
                                   std::span<const char> untagged_class = {});

}  // namespace mg
