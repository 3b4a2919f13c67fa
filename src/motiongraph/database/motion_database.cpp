#include "motiongraph/database/motion_database.h"

#include <algorithm>

namespace mg {

int MotionDatabase::clip_of(int frame) const {
  auto it = std::upper_bound(clips.begin(), clips.end(), frame,
                             [](int f, const DatabaseClip& clip) { return f < clip.first_frame; });
  return static_cast<int>(it - clips.begin()) - 1;
}

std::vector<TagMask> MotionDatabase::frame_tags() const {
  std::vector<TagMask> tags(static_cast<size_t>(frame_count()), 0);
  for (const TagRange& range : tag_ranges) {
    for (int f = range.first_frame; f < range.first_frame + range.frame_count; ++f) {
      tags[f] |= TagMask{1} << range.tag;
    }
  }
  return tags;
}

int MotionDatabase::tag_index(const std::string& name) {
  auto it = std::find(tag_names.begin(), tag_names.end(), name);
  if (it != tag_names.end()) return static_cast<int>(it - tag_names.begin());
  if (tag_names.size() >= 64) return -1;
  tag_names.push_back(name);
  return static_cast<int>(tag_names.size()) - 1;
}

std::vector<std::string> MotionDatabase::tag_names_of(TagMask mask) const {
  std::vector<std::string> names;
  for (size_t t = 0; t < tag_names.size(); ++t) {
    if (mask >> t & 1) names.push_back(tag_names[t]);
  }
  return names;
}

}  // namespace mg
