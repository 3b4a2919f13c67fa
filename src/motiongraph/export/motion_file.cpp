#include "motiongraph/export/motion_file.h"

#include <filesystem>

#include <fmt/format.h>

#include "motiongraph/core/file_extension.h"
#include "motiongraph/export/bvh_writer.h"
#include "motiongraph/export/fbx_writer.h"
#include "motiongraph/export/gltf_writer.h"
#include "motiongraph/io/file.h"
#include "motiongraph/motion/rig_matching.h"
#include "motiongraph/motion/trajectory_joint.h"

namespace mg {

Status check_motion_output(const std::string& path) {
  const std::string ext = lower_extension(path);
  if (ext != ".bvh" && ext != ".json" && !is_scene_extension(ext)) {
    return Error{path, 0, "output must end in .bvh, .glb, .gltf, .fbx or .json"};
  }
  return Ok{};
}

bool is_scene_extension(const std::string& ext) { return ext == ".glb" || ext == ".gltf" || ext == ".fbx"; }

Result<std::string> scene_bytes(const std::string& ext, const Skeleton& skeleton,
                                std::span<const ExportAnimation> animations, bool figure) {
  if (ext == ".glb" || ext == ".gltf") {
    return write_gltf_file(skeleton, animations, GltfWriteSettings{figure}, ext == ".glb");
  }
  if (ext == ".fbx") return write_fbx(skeleton, animations, FbxWriteSettings{figure});
  return Error{"", 0, fmt::format("'{}' is no scene format ({})", ext, kSceneFormats)};
}

Status MotionFileSettings::validate() const {
  BvhWriteSettings bvh;
  bvh.units_per_metre = units_per_metre;
  if (auto s = bvh.validate(); !s) return s;
  if (root_motion) return root_motion->settings.validate();
  return Ok{};
}

Result<std::string> motion_file_bytes(const std::string& path, const Skeleton& skeleton, const Motion& motion,
                                      const MotionFileSettings& settings, const PositionsJsonContacts* contacts) {
  if (auto s = check_motion_output(path); !s) return s.error();
  if (auto s = settings.validate(); !s) return Error{path, 0, s.error().message};
  if (const auto& root_motion = settings.root_motion) {
    auto added = add_root_motion(skeleton, motion, root_motion->forward_axis, root_motion->settings);
    if (!added) return Error{path, 0, added.error().message};
    // The feet are one joint further on.
    std::optional<PositionsJsonContacts> shifted;
    if (contacts) {
      shifted = *contacts;
      for (Foot* foot : {&shifted->feet.left, &shifted->feet.right}) {
        foot->ankle += 1;
        if (foot->toe >= 0) foot->toe += 1;
      }
    }
    MotionFileSettings added_settings = settings;
    added_settings.root_motion.reset();
    return motion_file_bytes(path, added->skeleton, added->motion, added_settings, shifted ? &*shifted : nullptr);
  }
  BvhWriteSettings write;
  write.units_per_metre = settings.units_per_metre;
  write.keep_root_order = settings.keep_root_order;
  const std::string ext = lower_extension(path);
  if (is_scene_extension(ext)) {
    // The animation is named as the file (an engine lists every imported file's as its name).
    const std::string stem = std::filesystem::path(path).stem().string();
    const std::string name = !settings.animation_name.empty() ? settings.animation_name
                             : stem.empty()                   ? std::string("motion")
                                                              : stem;
    const ExportAnimation animation{name, &motion};
    auto bytes = scene_bytes(ext, skeleton, std::span(&animation, 1), settings.figure);
    if (!bytes) return Error{path, 0, bytes.error().message};
    return bytes;
  }
  return ext == ".bvh" ? write_bvh(skeleton, motion, write) : write_positions_json(skeleton, motion, contacts);
}

Status write_motion(const std::string& path, const Skeleton& skeleton, const Motion& motion,
                    const MotionFileSettings& settings, const PositionsJsonContacts* contacts) {
  auto bytes = motion_file_bytes(path, skeleton, motion, settings, contacts);
  if (!bytes) return bytes.error();
  return write_file_atomic(path, *bytes);
}

Status write_animation_set(const std::string& path, std::span<const NamedMotion> motions,
                           const MotionFileSettings& settings) {
  const std::string ext = lower_extension(path);
  if (!is_scene_extension(ext)) {
    return Error{path, 0, fmt::format("several motions go into a {} only (an animation each)", kSceneFormats)};
  }
  if (auto s = settings.validate(); !s) return Error{path, 0, s.error().message};
  if (motions.empty()) return Error{path, 0, "no motion to write"};
  for (const NamedMotion& m : motions) {
    if (m.motion->frame_count == 0) return Error{m.source, 0, "has no frames: an animation needs one"};
  }
  // A held pose of a rig with a static root above the hips did not fold it (its hips never
  // travel): folded as the clips that did, it is their rig (motion/trajectory_joint.h).
  std::vector<NamedMotion> same(motions.begin(), motions.end());
  std::vector<Clip> refolded;
  refolded.reserve(same.size());
  const auto folded = std::find_if(same.begin(), same.end(),
                                   [](const NamedMotion& m) { return !m.skeleton->static_ancestors().empty(); });
  if (folded != same.end()) {
    const Skeleton reference = *folded->skeleton;
    const Vec3 reference_axis = folded->forward_axis;
    for (NamedMotion& m : same) {
      if (m.skeleton->static_ancestors().size() >= reference.static_ancestors().size()) continue;
      Clip clip;
      clip.skeleton = *m.skeleton;
      clip.motion = *m.motion;
      refolded.push_back(fold_as(clip, reference));
      m.skeleton = &refolded.back().skeleton;
      m.motion = &refolded.back().motion;
      // Its forward axis was learnt in the frame of the root it had; now the folded clips' root.
      if (m.skeleton->static_ancestors().size() == reference.static_ancestors().size()) m.forward_axis = reference_axis;
    }
  }
  for (const NamedMotion& m : same) {
    if (auto why = rig_difference(*same.front().skeleton, *m.skeleton)) {
      return Error{m.source, 0,
                   fmt::format("its rig is not {}'s ({}): one {} holds one skeleton (a library read as one puts "
                               "its clips on one rig: convert FOLDER, Python's load_library)",
                               same.front().source, *why, ext)};
    }
  }
  motions = same;
  // With root motion, each motion on its own skeleton with the joint added (the same rig again).
  std::vector<RootMotionClip> added;
  if (const auto& root_motion = settings.root_motion) {
    for (const NamedMotion& m : motions) {
      auto clip = add_root_motion(*m.skeleton, *m.motion, m.forward_axis, root_motion->settings);
      if (!clip) return Error{m.source, 0, clip.error().message};
      added.push_back(std::move(*clip));
    }
  }
  const Skeleton& skeleton = added.empty() ? *motions.front().skeleton : added.front().skeleton;
  std::vector<ExportAnimation> animations;
  for (size_t i = 0; i < motions.size(); ++i) {
    animations.push_back({motions[i].name, added.empty() ? motions[i].motion : &added[i].motion});
  }
  auto bytes = scene_bytes(ext, skeleton, animations, settings.figure);
  if (!bytes) return Error{path, 0, bytes.error().message};
  return write_file_atomic(path, *bytes);
}

Result<std::optional<ClipContacts>> clip_contacts(const Skeleton& skeleton, const Motion& motion,
                                                  const FootJointNames& names, std::string& why) {
  auto found = find_foot_joints(skeleton, names);
  if (!found) {
    if (!names.empty()) return found.error();
    why = found.error().message;
    return std::optional<ClipContacts>();
  }
  auto contacts = detect_foot_contacts(skeleton, motion, *found, FootContactSettings{});
  if (!contacts) return contacts.error();
  ClipContacts out{*found, std::vector<ContactMask>(static_cast<size_t>(motion.frame_count))};
  for (int f = 0; f < motion.frame_count; ++f) out.masks[f] = contact_mask(*contacts, f);
  return std::optional<ClipContacts>(std::move(out));
}

}  // namespace mg
