// An FBX file (ASCII, FBX 7.4) built from clips for the tests, by FBX's rules as Maya and Mixamo
// write them: every joint a LimbNode under an "Armature" Null node, resting turned in its own frame
// (each joint's axes turned by a rotation of its own, as bones along themselves are), with a
// PreRotation and a rotation order of its own (all six in turn), Euler keys in degrees at the
// clip's rate; the root's translation keyed; lengths in the file's unit (centimetres times
// `unit_scale_factor`) under an armature turned and scaled; any axis up (our +y turned to it the
// shortest way, as the reader turns it back; half a turn about x for -y). Each clip is an animation
// stack (all on one skeleton, named as given). With `skin`, a mesh skinned to every joint (or every
// joint with a child: `skin_leaves`) and an
// animated prop beside the armature, which is not a joint. So each clip's joints lie where the
// clip puts them, and nothing of the file says so but its rules.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "motiongraph/motion/motion.h"

namespace mg::test {

struct AsciiFbxSettings {
  std::string up = "+y";           // "+y", "+z", "-z", "+x", "-x", "-y"
  double unit_scale_factor = 1.0;  // FBX's unit: centimetres times this
  double armature_scale = 1.0;     // the Armature node's (uniform) scale
  Quat armature_rotation = Quat::Identity();
  bool skin = false;
  bool skin_leaves = true;  // false: joints without children get no cluster (Mixamo's end bones)
  std::string stack_prefix;  // e.g. "Armature|", as Blender names its stacks
};

// `clips`: (stack name, clip), every clip on the first's skeleton, whose only translated joint is
// its root.
std::string ascii_fbx(const std::vector<std::pair<std::string, Clip>>& clips, const AsciiFbxSettings& settings = {});

}  // namespace mg::test
