// Foot slide on the frames a result plays, beside the same frames in the capture.
#include "motiongraph/evaluation/same_frames_slide.h"

#include <array>
#include <cmath>
#include <fmt/format.h>

#include "motiongraph/motion/forward_kinematics.h"
#include "motiongraph/synthesis/facing.h"

namespace mg {

namespace {

constexpr int kKinds = 4;  // left ankle, left toe, right ankle, right toe

int kind_of(FootSide side, FootPart part) { return 2 * static_cast<int>(side) + static_cast<int>(part); }

std::array<int, kKinds> kind_joints(const FootJoints& feet) {
  return {feet.left.ankle, feet.left.toe, feet.right.ankle, feet.right.toe};
}

// One clip's measured joints: their floor positions and contacts, per local frame.
struct ClipFeet {
  bool read = false;
  std::array<std::vector<Vec2>, kKinds> floor;       // (x, z) per frame; empty: no such joint
  std::array<std::vector<double>, kKinds> height;    // y per frame
  std::array<std::vector<uint8_t>, kKinds> planted;  // per frame
};

// The measure's contacts for one clip, on its own skeleton.
Status read_clip(const MotionDatabase& db, int c, const FootSlideSettings& settings, ClipFeet& out) {
  const DatabaseClip& clip = db.clips[c];
  const Skeleton& skeleton = db.skeletons[clip.skeleton];
  auto feet = find_foot_joints(skeleton, settings.joint_names);
  if (!feet) return Error{clip.name, 0, feet.error().message};
  const std::vector<Vec3> positions = world_positions(skeleton, clip.motion);
  auto contacts = detect_foot_contacts(positions, skeleton.joint_count(), clip.motion.fps, *feet, settings.contacts);
  if (!contacts) return Error{clip.name, 0, contacts.error().message};
  const size_t joints = static_cast<size_t>(skeleton.joint_count());
  for (const FootContactTrack& track : contacts->tracks) {
    const int kind = kind_of(track.side, track.part);
    out.planted[kind] = track.planted;
    out.floor[kind].resize(static_cast<size_t>(clip.frame_count));
    out.height[kind].resize(static_cast<size_t>(clip.frame_count));
    for (size_t f = 0; f < out.floor[kind].size(); ++f) {
      const Vec3& p = positions[f * joints + static_cast<size_t>(track.joint)];
      out.floor[kind][f] = Vec2(p.x(), p.z());
      out.height[kind][f] = p.y();
    }
  }
  out.read = true;
  return Ok{};
}

}  // namespace

Result<SameFramesSlide> same_frames_foot_slide(const MotionDatabase& db, const MotionAssembler& assembler,
                                               const Motion& output, std::span<const FrameSource> sources,
                                               const FootSlideSettings& settings) {
  if (auto valid = settings.validate(); !valid) return valid.error();
  if (static_cast<int>(sources.size()) < output.frame_count) {
    return Error{"", 0, fmt::format("{} frames but the sources of {}", output.frame_count, sources.size())};
  }
  const Skeleton& skeleton = assembler.skeleton();
  auto feet = find_foot_joints(skeleton, settings.joint_names);
  if (!feet) return feet.error();
  // The joints measured on the result, by kind: each foot's toe, else its ankle; with
  // include_ankles the ankles as well.
  const std::array<int, kKinds> joint = kind_joints(*feet);
  std::array<bool, kKinds> measured{};
  for (int side = 0; side < 2; ++side) {
    const int ankle = 2 * side, toe = 2 * side + 1;
    measured[toe] = joint[toe] >= 0;
    measured[ankle] = joint[ankle] >= 0 && (joint[toe] < 0 || settings.include_ankles);
  }
  const std::vector<Vec3> positions = world_positions(skeleton, output);
  const size_t joints = static_cast<size_t>(skeleton.joint_count());
  const double fps = output.fps;

  std::vector<ClipFeet> clips(db.clips.size());
  auto clip_feet = [&](int c) -> Result<const ClipFeet*> {
    if (!clips[c].read) {
      if (auto s = read_clip(db, c, settings, clips[c]); !s) return s.error();
    }
    return &clips[c];
  };
  // A joint at database frame x as the capture has it, in the result's scale: its horizontal
  // speed into the frame (out of it at its clip's first frame) and its height; NaN where x's clip
  // has no joint of that kind (the speed too in a clip of one frame).
  struct Captured {
    double speed_mps, height_m;
  };
  auto captured_at = [&](int x, int kind) -> Result<Captured> {
    const int c = db.clip_of(x);
    auto got = clip_feet(c);
    if (!got) return got.error();
    const std::vector<Vec2>& track = (*got)->floor[kind];
    const std::vector<double>& heights = (*got)->height[kind];
    const double scale = assembler.scale_of(db.clips[c].skeleton);
    const int local = x - db.clips[c].first_frame;
    Captured at{std::nan(""), std::nan("")};
    if (!heights.empty()) at.height_m = heights[static_cast<size_t>(local)] * scale;
    if (track.size() >= 2) {
      const size_t i = static_cast<size_t>(std::max(local, 1));
      at.speed_mps = (track[i] - track[i - 1]).norm() * fps * scale;
    }
    return at;
  };

  SameFramesSlide slide;
  double output_sum = 0.0, source_sum = 0.0;
  for (int f = 1; f < output.frame_count; ++f) {
    const FrameSource& from = sources[f];
    const int g = from.dominant();
    const int c = db.clip_of(g);
    const int local = g - db.clips[c].first_frame;
    if (local < 1) continue;
    auto got = clip_feet(c);
    if (!got) return got.error();
    for (int kind = 0; kind < kKinds; ++kind) {
      if (!measured[kind]) continue;
      const std::vector<uint8_t>& planted = (*got)->planted[kind];
      if (planted.empty() || !planted[local - 1] || !planted[local]) continue;
      auto departure = captured_at(from.departure, kind);
      if (!departure) return departure.error();
      auto arrival = captured_at(from.arrival, kind);
      if (!arrival) return arrival.error();
      // Lifted off the floor in the result (a foot stepping to a new plant): above the height
      // the capture's frames give the joint, blended as the frame blends them.
      const double captured = from.alpha * departure->height_m + (1.0 - from.alpha) * arrival->height_m;
      const double height = positions[static_cast<size_t>(f) * joints + joint[kind]].y();
      if (height > captured + settings.contacts.enter_height_m) {
        ++slide.lifted_steps;
        continue;
      }
      const double source = from.alpha * departure->speed_mps + (1.0 - from.alpha) * arrival->speed_mps;
      if (std::isnan(source)) continue;
      const Vec3 step = positions[static_cast<size_t>(f) * joints + joint[kind]] -
                        positions[static_cast<size_t>(f - 1) * joints + joint[kind]];
      output_sum += std::hypot(step.x(), step.z()) * fps;
      source_sum += source;
      ++slide.steps;
    }
  }
  if (slide.steps > 0) {
    slide.mean_mps = output_sum / static_cast<double>(slide.steps);
    slide.source_mean_mps = source_sum / static_cast<double>(slide.steps);
  }
  return slide;
}

}  // namespace mg
