#include "motion/static_root_bvh.h"

#include <numbers>
#include <optional>

#include <fmt/format.h>

namespace mg::test {

namespace {

constexpr double kDegrees = 180.0 / std::numbers::pi;

std::string channels_line(const std::string& indent, const ComposeOrder& order) {
  return fmt::format("{}CHANNELS 6 Xposition Yposition Zposition {}rotation {}rotation {}rotation\n", indent,
                     axis_letter(order[0]), axis_letter(order[1]), axis_letter(order[2]));
}

void put_values(std::string& line, const Vec3& translation_units, const Vec3& angles_deg) {
  for (int i = 0; i < 3; ++i) line += fmt::format(" {:.6f}", translation_units[i]);
  for (int i = 0; i < 3; ++i) line += fmt::format(" {:.6f}", angles_deg[i]);
}

}  // namespace

std::string static_root_bvh(const Clip& clip, const Vec3& root_translation_m, const Quat& root_rotation,
                            double units_per_metre) {
  const Skeleton& skeleton = clip.skeleton;
  const int joints = skeleton.joint_count();
  std::vector<std::vector<int>> children(static_cast<size_t>(joints));
  for (int j = 1; j < joints; ++j) children[skeleton.parent(j)].push_back(j);
  const ComposeOrder root_order{Axis::kZ, Axis::kX, Axis::kY};

  // Hierarchy, depth first; `order` is the joints whose channels follow, in file order.
  std::string out = "HIERARCHY\nROOT " + std::string(kStaticRootName) + "\n{\n  OFFSET 0 0 0\n" +
                    channels_line("  ", root_order);
  std::vector<int> order;
  const auto write_joint = [&](const auto& self, int j, int depth) -> void {
    const std::string indent(static_cast<size_t>(depth) * 2, ' ');
    const JointDef& joint = skeleton.joint(j);
    const Vec3 offset = joint.rest_offset_m * units_per_metre;
    if (joint.end_site) {
      out += fmt::format("{}End Site\n{}{{\n{}  OFFSET {:.6f} {:.6f} {:.6f}\n{}}}\n", indent, indent, indent, offset.x(),
                         offset.y(), offset.z(), indent);
      return;
    }
    order.push_back(j);
    out += fmt::format("{}JOINT {}\n{}{{\n{}  OFFSET {:.6f} {:.6f} {:.6f}\n", indent, joint.name, indent, indent,
                       offset.x(), offset.y(), offset.z());
    out += channels_line(indent + "  ", joint.euler_order);
    for (int child : children[j]) self(self, child, depth + 1);
    if (children[j].empty()) out += fmt::format("{0}  End Site\n{0}  {{\n{0}    OFFSET 0 0 0\n{0}  }}\n", indent);
    out += indent + "}\n";
  };
  write_joint(write_joint, 0, 1);
  out += "}\n";

  const Motion& motion = clip.motion;
  out += fmt::format("MOTION\nFrames: {}\nFrame Time: {:.9g}\n", motion.frame_count, 1.0 / motion.fps);
  const Quat inverse_root = root_rotation.conjugate();
  const Vec3 root_angles = decompose_euler(root_order, root_rotation) * kDegrees;
  std::vector<std::optional<Vec3>> previous(static_cast<size_t>(joints));
  for (int f = 0; f < motion.frame_count; ++f) {
    std::string line;
    put_values(line, root_translation_m * units_per_metre, root_angles);
    for (int j : order) {
      const int slot = skeleton.translation_slot(j);
      Vec3 translation = slot >= 0 ? motion.translations(f)[slot] : skeleton.joint(j).rest_offset_m;
      Quat rotation = motion.rotations(f)[j];
      if (j == 0) {  // relative to the static root
        translation = inverse_root * (translation - root_translation_m);
        rotation = inverse_root * rotation;
      }
      const Vec3 angles = decompose_euler(skeleton.joint(j).euler_order, rotation, previous[j]);
      previous[j] = angles;
      put_values(line, translation * units_per_metre, angles * kDegrees);
    }
    out += line.substr(1) + "\n";
  }
  return out;
}

Clip translation_root_clip(const Clip& walk, const Quat& turn, double yaw_per_frame, bool ik) {
  std::vector<JointDef> joints;
  JointDef top;
  top.name = "root_motion";
  top.animated_translation = true;
  joints.push_back(top);
  for (const JointDef& joint : walk.skeleton.joints()) {
    JointDef moved = joint;
    moved.parent = joint.parent + 1;
    joints.push_back(moved);
  }
  if (ik) {
    JointDef helper;
    helper.name = "ik_foot_l";
    helper.parent = 0;
    helper.rest_offset_m = Vec3(0.1, 0.0, 0.05);
    joints.push_back(helper);
  }
  Clip out;
  out.name = walk.name;
  out.skeleton = Skeleton(std::move(joints));
  out.motion = Motion(out.skeleton, walk.motion.frame_count, walk.motion.fps);
  for (int f = 0; f < walk.motion.frame_count; ++f) {
    const Vec3 hips = walk.motion.translations(f)[0];
    const Quat hips_rotation = walk.motion.rotations(f)[0];
    const Quat r = (turn * Quat(Eigen::AngleAxisd(yaw_per_frame * f, Vec3::UnitY()))).normalized();
    const Vec3 t(hips.x(), 0.0, hips.z());
    auto rotations = out.motion.rotations(f);
    auto translations = out.motion.translations(f);
    rotations[0] = r;
    translations[out.skeleton.translation_slot(0)] = t;
    rotations[1] = (r.conjugate() * hips_rotation).normalized();
    translations[out.skeleton.translation_slot(1)] = r.conjugate() * (hips - t);
    for (int j = 1; j < walk.skeleton.joint_count(); ++j) {
      rotations[j + 1] = walk.motion.rotations(f)[j];
      const int slot = walk.skeleton.translation_slot(j);
      if (slot >= 0) translations[out.skeleton.translation_slot(j + 1)] = walk.motion.translations(f)[slot];
    }
    if (ik) rotations[out.skeleton.joint_count() - 1] = Quat::Identity();
  }
  return out;
}

}  // namespace mg::test
