// Which axis is up in a file that does not say (BVH, and ASF/AMC). Everything here is y up;
// most BVH is too, and CMU's ASF/AMC, but some tools write z up (3ds Max and its Biped, some
// MotionBuilder exports, capture systems whose world is z up). Read as y up, such a figure
// lies on the floor: its height is taken for a step across, its travel along z for a climb,
// and no path or floor alignment makes sense. BVH import (bvh_import.h) and the AMC loader
// (clip_loader.h) choose as below unless told.
//
// The choice is made on the figure's shape, the way length_unit.h chooses the unit: per frame
// the figure's extent along y and along z over all its joints, the median of each over the
// frames, and their ratio z / y. A standing or walking figure is about three times as tall as
// it is deep, so a ratio of kUpAxisRatio or more says z, one of 1 / kUpAxisRatio or less says
// y, and between the two the animation does not say (a T-pose has no depth to compare; a figure
// lying on the floor along x has neither). The rest pose (every rotation zero) is read the same
// way, as a second voice: it stands in the file's up axis whatever the clip does. z is chosen
// when the animation says z and the rest pose does not say y, or when the animation does not
// say and the rest pose says z; otherwise y (BVH's own convention). So a y-up clip of someone
// crawling along z keeps y when its rest pose stands, and a file whose root channels already
// turn a z-up rest pose upright (a converter's fix-up) keeps y.
//
// A z-up clip is turned y up by the rotation that takes +z to +y (-90 degrees about x, so that
// +y becomes -z): every rest offset and local translation is turned by it, and every local
// rotation conjugated by it (the static ancestors of a folded root too). Every world position
// is then the file's turned by that rotation, the rest pose stands in y, and the written BVH is
// a y-up file with the input's hierarchy.
#pragma once

#include <optional>
#include <span>
#include <string_view>

#include "motiongraph/motion/motion.h"
#include "motiongraph/motion/up_axis_choice.h"

namespace mg {

constexpr double kUpAxisRatio = 1.5;

std::string_view up_axis_name(UpAxis axis);  // "y", "z"
// "y" or "z" (either case); nullopt for anything else.
std::optional<UpAxis> parse_up_axis(std::string_view text);

// The choice above for a clip in its file's coordinates.
UpAxisChoice choose_up_axis(const Skeleton& skeleton, const Motion& motion);

// Whether a choice rests on evidence that agrees: the animation and the rest pose both say its
// axis, or one says it and the other is silent. A choice made against one of them (a z-up rest
// pose whose clip lies along y all through, or a converter's fix-up; a standing rest pose whose
// clip lies along z) or on neither (y by default) is not settled.
bool up_axis_settled(const UpAxisChoice& choice);

// The up axis of a library (the files of one database, one rig): the axis most of its settled
// choices have, provided the unsettled choices of the other axis are fewer than the settled ones
// of it; else nullopt (none settled, an even split, or too few to overrule the rest: a library of
// converter fix-ups, every one unsettled y, keeps y though one crawling clip settles z). A file
// whose own choice is not settled and differs from it is read in it (database_loader.h).
std::optional<UpAxis> library_up_axis(std::span<const UpAxisChoice> choices);

// The rotation that takes the file's up axis to +y (identity for y).
Quat up_axis_to_y(UpAxis axis);

// Every world position of the clip turned by `rotation` (as above), rest pose included.
void turn_clip(Clip& clip, const Quat& rotation);

// The clip turned y up from `given`, or when that is nullopt from the axis choose_up_axis
// finds, which is kept in clip.detected_up_axis.
void stand_up(Clip& clip, std::optional<UpAxis> given);

}  // namespace mg
