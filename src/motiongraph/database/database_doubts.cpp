// What looks wrong with each clip of a database as read (database_doubts.h).
#include "motiongraph/database/database_doubts.h"

#include <span>

#include "motiongraph/motion/clip_loader.h"
#include "motiongraph/motion/forward_kinematics.h"
#include "motiongraph/skeleton/foot_joints.h"

namespace mg {

std::vector<DoubtedClip> database_clip_doubts(const MotionDatabase& db, size_t clips) {
  // The feet the contacts were found for (their ankles judge a walk's pace).
  std::vector<FootJoints> feet;
  for (const Skeleton& skeleton : db.skeletons) {
    auto found = find_foot_joints(skeleton, db.foot_names);
    feet.push_back(found ? *found : FootJoints{});
  }
  std::vector<DoubtedClip> out;
  for (size_t c = 0; c < db.clips.size() && c < clips; ++c) {
    const DatabaseClip& clip = db.clips[c];
    const Skeleton& skeleton = db.skeletons[static_cast<size_t>(clip.skeleton)];
    const std::span<const ContactMask> contacts =
        db.frame_contacts.empty() ? std::span<const ContactMask>()
                                  : std::span<const ContactMask>(db.frame_contacts)
                                        .subspan(static_cast<size_t>(clip.first_frame),
                                                 static_cast<size_t>(clip.frame_count));
    // Keys timed in seconds (glTF, FBX): --input-fps only samples them.
    const ClipClock clock{clip.read_fps, is_gltf_file(clip.source) || is_fbx_file(clip.source)};
    out.push_back({clip.name,
                   clip_doubts(world_positions(skeleton, clip.motion), skeleton.joint_count(), db.fps, contacts, {},
                               clock, feet[static_cast<size_t>(clip.skeleton)]),
                   clock});
  }
  return out;
}

}  // namespace mg
