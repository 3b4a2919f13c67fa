// Which motion classes a candidate transition belongs to, per frame once.
#include "motiongraph/graph/window_membership.h"

namespace mg {

WindowMembership window_membership(std::span<const TagMask> frame_tags, TagMask tags, int window) {
  const int frames = static_cast<int>(frame_tags.size());
  std::vector<int> none_count(static_cast<size_t>(frames) + 1, 0);
  for (int f = 0; f < frames; ++f) none_count[f + 1] = none_count[f] + ((frame_tags[f] & tags) == 0 ? 1 : 0);
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
