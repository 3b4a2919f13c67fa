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
// carries, and whether every one of those frames carries none of them; 0 / false where the
// window leaves the data. A candidate belongs to a tag when both its windows carry it.
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

// For frames tagged `frame_tags` and windows of `window` frames.
WindowMembership window_membership(std::span<const TagMask> frame_tags, TagMask tags, int window);

}  // namespace mg
