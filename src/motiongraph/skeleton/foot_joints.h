// The feet of a skeleton: the left and right ankle joints and the toe joint below each, found
// by name. Foot contacts (motion/foot_contacts.h) and the foot-slide measure
// (evaluation/foot_slide.h) follow these joints (DESIGN.md section 5b).
//
// Rigs name their feet in many ways; a name is compared after folding away what varies
// between them: case, a namespace or path ("mixamorig:", "Armature|"), the separators
// '_', ' ', '-', '.', and a rig's prefix word ("mixamorig", "Bip01", "Character1", "DEF").
// What is left must be a side word and a part word, in either order:
//   side  left: "left", "l"       right: "right", "r"
//   ankle "ankle", else "foot"    (an ankle name wins: where a rig has both, as SMPL's
//                                  left_ankle/left_foot and Kinect's AnkleLeft/FootLeft,
//                                  the "foot" is the toe)
//   toe   "toebase", "toes", "toe", "toe0", "ball"
// So CMU ASF lfoot/ltoes, CMU BVH conversions LeftFoot/LeftToeBase, LeftAnkle/LeftToe and
// lfoot/ltoes, Daz lFoot, Mixamo mixamorig:LeftFoot/LeftToeBase, 3ds Max Bip01 L Foot/Toe0,
// Unreal foot_l/ball_l, Blender's foot.L/toe.L, Bandai Namco Foot_L/Toes_L.
//
// The toe is looked for below its ankle only (the nearest match). A rig with an ankle but no
// toe joint gets the ankle's only child when it has exactly one (an unnamed toe joint, or the
// End Site of a BVH foot such as Daz's lFoot, or an ASF leaf bone's end); else no toe, and the
// ankle alone stands for the foot.
//
// Names can also be given (FootJointNames, e.g. from a manifest): compared whole, ignoring
// case only. Fails with an error saying which joint was looked for and how.
#pragma once

#include <string>
#include <string_view>

#include "motiongraph/core/error.h"
#include "motiongraph/skeleton/skeleton.h"

namespace mg {

struct Foot {
  int ankle = -1;  // joint index
  int toe = -1;    // joint index below the ankle; -1: none (the ankle alone)
};

struct FootJoints {
  Foot left;
  Foot right;
};

// Joint names to use instead of finding them; an empty name is found as above (a toe then
// below the ankle given or found).
struct FootJointNames {
  std::string left_ankle;
  std::string left_toe;
  std::string right_ankle;
  std::string right_toe;

  Status validate() const;
  // No name given: every joint found.
  bool empty() const { return left_ankle.empty() && left_toe.empty() && right_ankle.empty() && right_toe.empty(); }
  bool operator==(const FootJointNames&) const = default;
};

// "LEFT_ANKLE,LEFT_TOE,RIGHT_ANKLE,RIGHT_TOE" (the CLI's --feet): four names, any of them empty
// to find that joint ("LeftFoot,,RightFoot,"). Fails on another count or a rule validate() names.
Result<FootJointNames> parse_foot_joint_names(std::string_view text);

// The feet of `skeleton` (see above). Fails when a foot has no ankle, when a named joint is
// missing, or when a named toe is not below its ankle.
Result<FootJoints> find_foot_joints(const Skeleton& skeleton, const FootJointNames& names = {});

// The name folded as above ("mixamorig:Left_Foot" -> "leftfoot"), for tests and messages.
std::string folded_joint_name(std::string_view name);

}  // namespace mg
