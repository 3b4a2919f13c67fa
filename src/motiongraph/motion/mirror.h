// A clip mirrored left to right: the same motion as its mirror image would play it, on the same
// skeleton. A library whose walks turn only left (a studio's walk_turn_left and no right turn)
// then turns right too, as game engines' motion matching mirrors its data.
//
// The mirror's plane is the rest pose's: joints pair by their names (lfemur / rfemur,
// LeftUpLeg / RightUpLeg, mixamorig:LeftArm, L_Hip / R_Hip, Hip_L / Hip_R, hip.L / hip.R,
// "Bip01 L Thigh"), a joint of the middle (the spine, the head) pairs with itself, and an end
// site takes its parent's partner's. The plane's normal n is the line across the body where it
// first parts into paired joints that stand apart in the rest pose (every local rotation the
// identity: world_j = world_parent * Translate(rest_offset_j)), the hips, on the floor; the
// reflection is M = I - 2 n n^T. The hips, not all the pairs: they are what facing.h faces
// square to, so a mirrored clip faces the way it travels, and an arm held higher than the other
// in the rest pose does not tilt the plane.
//
// With every joint's world rotation G_j (the identity in the rest pose), the mirrored motion's
// partner j' turns by M G_j M and stands at M p_j: its local rotation is M L_j M (quaternion
// (w, v) -> (w, -M v)), the root's translation t becomes M t - 2 d G'_root n (d the plane's
// distance from the root, G'_root the root's mirrored rotation: a root off the plane stands off
// it on the other side), and another joint's animated
// translation t_j becomes M t_j + (rest_offset_j' - M rest_offset_j), so that where the two sides
// differ a little (a captured subject's bones) the mirrored motion keeps the skeleton's own bones,
// whether its joints translate (BVH with six channels on every joint) or not. Where the rest pose
// is the mirror image of itself, every joint of the mirrored motion stands at the mirror image of
// its partner's place. Mirrored twice, a motion is itself again.
//
// A skeleton cannot be mirrored (mirror_map fails, saying why) when no joint pairs, a pair's
// parents are not partners, only one of a pair has animated translation, the hips lie one above
// the other (more than 10 degrees: the rest pose lies on its side), or the rest pose is not its
// own mirror image within 5 % of its size (naming the joint furthest off).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "motiongraph/core/error.h"
#include "motiongraph/motion/motion.h"

namespace mg {

struct MirrorMap {
  std::vector<int> partner;     // per joint: its mirror image (itself on the middle)
  Vec3 normal = Vec3::UnitX();  // unit, on the floor, across the body (either way)
  int pairs = 0;                // joints paired with another (each pair once)
  double asymmetry_m = 0.0;     // the rest pose's largest distance of a joint from its partner's mirror image
  // The plane's distance from the root joint along `normal`, in the root's frame: a root beside
  // the hips' middle (a rig's hips joint a few centimetres off), whose mirrored translation takes
  // it back so that the body, not the root, is mirrored in place.
  double plane_offset_m = 0.0;
};

// The joint names a name's mirror image may have, the left / right words and letters swapped
// one at a time ("LeftUpLeg" -> "RightUpLeg", "lfemur" -> "rfemur", "Hip_L" -> "Hip_R").
std::vector<std::string> mirrored_names(std::string_view name);

// `text` with each word left and right swapped ("turn_left" -> "turn_right", "LeftStep" ->
// "RightStep"): the name of a tag or a clip on the mirror's side.
std::string mirrored_side_words(std::string_view text);

Result<MirrorMap> mirror_map(const Skeleton& skeleton);

// `motion` (on `skeleton`, of which `map` is the mirror map) mirrored.
Motion mirror_motion(const Skeleton& skeleton, const MirrorMap& map, const Motion& motion);

}  // namespace mg
