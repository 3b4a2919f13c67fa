// Which motion classes a candidate transition belongs to, per frame once.
#include "motiongraph/graph/window_membership.h"

#include <algorithm>

namespace mg {

std::vector<char> untagged_class_frames(const MotionDatabase& db, TagMask tags) {
  const std::vector<TagMask> frame_tags = db.frame_tags();
  std::vector<char> in_class(frame_tags.size(), 0);
  for (const DatabaseClip& clip : db.clips) {
    const auto first = frame_tags.begin() + clip.first_frame, last = first + clip.frame_count;
    if (std::none_of(first, last, [&](TagMask m) { return (m & tags) != 0; })) {
      std::fill_n(in_class.begin() + clip.first_frame, clip.frame_count, 1);
    }
  }
  return in_class;
}

WindowMembership window_membership(std::span<const TagMask> frame_tags, TagMask tags, int window,
                                   std::span<const char> untagged_class) {
  const int frames = static_cast<int>(frame_tags.size());
  const bool classed = untagged_class.size() == frame_tags.size();
  std::vector<int> none_count(static_cast<size_t>(frames) + 1, 0);
  for (int f = 0; f < frames; ++f) {
    const bool none = classed ? untagged_class[f] != 0 : (frame_tags[f] & tags) == 0;
    none_count[f + 1] = none_count[f] + (none ? 1 : 0);
  }
  auto all_none = [&](int first, int last) {
    return first >= 0 && last < frames && none_count[last + 1] - none_count[first] == last - first + 1;
  };
  auto all_carry = [&](int first, int last) {
    if (first < 0 || last >= frames) return TagMask{0};
    TagMask m = ~TagMask{0};
    for (int f = first; f <= last; ++f) m &= frame_tags[f];
    return m;
  };
  WindowMembership out;
  out.leave.resize(static_cast<size_t>(frames));
  out.arrive.resize(static_cast<size_t>(frames));
  out.leave_none.resize(static_cast<size_t>(frames));
  out.arrive_none.resize(static_cast<size_t>(frames));
  for (int f = 0; f < frames; ++f) {
    out.leave[f] = all_carry(f, f + window - 1) & tags;
    out.arrive[f] = all_carry(f - window + 1, f) & tags;
    out.leave_none[f] = all_none(f, f + window - 1);
    out.arrive_none[f] = all_none(f - window + 1, f);
  }
  return out;
}

}  // namespace mg
