// What looks wrong with each clip of a database as read (motion/clip_doubts.h): its size, floor,
// feet or clock, judged at the database's rate on the contacts found at loading, each skeleton's
// feet found as they were for them, each clip's clock as it was read (glTF and FBX keys timed in
// seconds). What loading warns of, and what the studio lists for a graph file's clips.
#pragma once

#include <cstdint>
#include <vector>

#include "motiongraph/database/motion_database.h"
#include "motiongraph/motion/clip_doubts.h"

namespace mg {

// One per clip, in clip order (empty doubts for a clip that looks right); of the first `clips`
// alone when fewer (loading leaves out the mirrored ones, whose doubts are their clips').
std::vector<DoubtedClip> database_clip_doubts(const MotionDatabase& db, size_t clips = SIZE_MAX);

}  // namespace mg
