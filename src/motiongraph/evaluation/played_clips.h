// What a synthesized motion plays, in order, as a user reads a result: the pieces of clips and
// the blends between them, each at the second of the output it starts. The reports of walk, path
// and steer carry it as "played", so that which clip played when needs no graph file to look up.
//
// From each output frame's source (synthesis/assembler.h FrameSource): a frame of one clip (its
// blend weight 0 or 1) goes on a piece, {"at_s", "seconds", "clip", "first_frame",
// "last_frame"} (the clip's own frames at the database's rate; a piece goes on while the frames
// follow on in the clip, or hold one, as a rest holds its last); the frames that mix two
// (a transition's blend, a start from rest) make a blend, {"at_s", "seconds", "blend_from",
// "blend_to"}, the clips it leaves and arrives in.
#pragma once

#include <span>

#include <nlohmann/json.hpp>

#include "motiongraph/database/motion_database.h"
#include "motiongraph/synthesis/assembler.h"

namespace mg {

// Of the first `frames` sources (the output's frames: a path cut at its end plays fewer than its
// walk's sources).
nlohmann::json played_clips_json(const MotionDatabase& db, std::span<const FrameSource> sources, double fps,
                                 int frames);

}  // namespace mg
