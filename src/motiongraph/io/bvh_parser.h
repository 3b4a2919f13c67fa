// Biovision Hierarchy (BVH) parser: text in memory -> BvhDocument, the joints, channels and
// channel values as written (file units, degrees). Building a skeleton and motion from it is
// skeleton/bvh_skeleton.h.
//
// Accepts any rotation order per joint, any subset of the six channels per joint (position
// channels give the joint's local translation in place of OFFSET), End Site, LF or CRLF, tabs,
// keywords and channel names in any case ("End site", "zrotation").
// Rejects: duplicate joint names, unbalanced braces, a 'Frames:' count that differs from the
// motion lines, 'Frame Time' <= 0, a line with the wrong number of values, non-finite values.
// A huge 'Frames:' value allocates nothing: storage grows with the lines actually present.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "motiongraph/core/error.h"
#include "motiongraph/skeleton/rotation.h"

namespace mg {

enum class BvhChannel { kXposition, kYposition, kZposition, kXrotation, kYrotation, kZrotation };

const char* bvh_channel_name(BvhChannel channel);
bool is_rotation(BvhChannel channel);
Axis channel_axis(BvhChannel channel);

struct BvhJoint {
  int line = 0;
  std::string name;            // End Sites get "<parent>_end" (made unique)
  int parent = -1;
  bool end_site = false;
  Vec3 offset = Vec3::Zero();  // file units
  std::vector<BvhChannel> channels;
  int first_channel = 0;       // index of its first value in a motion line
};

struct BvhDocument {
  std::string file_name;
  std::vector<BvhJoint> joints;  // depth-first, as in the file (parents first)
  int channel_count = 0;
  int frame_count = 0;
  double frame_time_s = 0.0;
  int frame_time_line = 0;       // the line of 'Frame Time:'
  std::vector<double> values;    // frame_count x channel_count
};

Result<BvhDocument> parse_bvh(std::string_view text, std::string file_name);

}  // namespace mg
