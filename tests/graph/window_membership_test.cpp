// A candidate's classes from the per-frame masks (and a given untagged class), against the
// definition checked frame by frame.
#include "motiongraph/graph/window_membership.h"

#include <random>

#include <gtest/gtest.h>

namespace mg {
namespace {

TEST(WindowMembership, ACandidateBelongsToWhatEveryFrameOfBothWindowsCarries) {
  std::mt19937 rng(20261202);
  long long members = 0, untagged = 0, outside = 0, classed_members = 0;
  for (int round = 0; round < 40; ++round) {
    const int frames = 60 + static_cast<int>(rng() % 60), window = 1 + static_cast<int>(rng() % 8);
    std::vector<TagMask> frame_tags(static_cast<size_t>(frames));
    for (int f = 0; f < frames;) {  // runs of one mask (tags 0-3, or none)
      const TagMask one = TagMask{1} << (rng() % 4), another = rng() % 3 == 0 ? TagMask{1} << (rng() % 4) : 0;
      const TagMask m = rng() % 4 == 0 ? 0 : one | another;
      for (int n = 3 + static_cast<int>(rng() % 20); n > 0 && f < frames; --n) frame_tags[f++] = m;
    }
    const TagMask tags = 0b0111;  // tag 3 is not asked about
    const WindowMembership windows = window_membership(frame_tags, tags, window);
    // The untagged class given (as whole clips are): runs of frames in it or not.
    std::vector<char> in_class(static_cast<size_t>(frames));
    for (int f = 0; f < frames;) {
      const char c = rng() % 2 == 0 ? 1 : 0;
      for (int n = 3 + static_cast<int>(rng() % 25); n > 0 && f < frames; --n) in_class[f++] = c;
    }
    const WindowMembership classed = window_membership(frame_tags, tags, window, in_class);
    for (int i = 0; i < 200; ++i) {
      const Transition c{static_cast<int>(rng() % (frames + 4)) - 2, static_cast<int>(rng() % (frames + 4)) - 2};
      const int first[2] = {c.from_frame, c.to_frame - window + 1};
      bool inside = true, none = true, of_class = true;
      TagMask all = ~TagMask{0};
      for (const int start : first) {
        for (int f = start; f < start + window; ++f) {
          if (f < 0 || f >= frames) {
            inside = false;
            continue;
          }
          all &= frame_tags[f];
          none = none && (frame_tags[f] & tags) == 0;
          of_class = of_class && in_class[f] != 0;
        }
      }
      EXPECT_EQ(classed.tags_of(c), windows.tags_of(c));
      EXPECT_EQ(classed.untagged(c), inside && of_class) << round;
      EXPECT_EQ(classed.belongs(c, -1), inside && of_class) << round;
      classed_members += inside && of_class ? 1 : 0;
      EXPECT_EQ(windows.tags_of(c), inside ? all & tags : 0) << round << ": " << c.from_frame << "->" << c.to_frame;
      EXPECT_EQ(windows.untagged(c), inside && none) << round;
      for (int t = -1; t < 4; ++t) {
        EXPECT_EQ(windows.belongs(c, t), t >= 0 ? (windows.tags_of(c) >> t & 1) != 0 : windows.untagged(c));
      }
      members += windows.tags_of(c) != 0 ? 1 : 0;
      untagged += windows.untagged(c) ? 1 : 0;
      outside += inside ? 0 : 1;
    }
  }
  // The rounds reach every case.
  EXPECT_GT(members, 100);
  EXPECT_GT(untagged, 20);
  EXPECT_GT(outside, 20);
  EXPECT_GT(classed_members, 100);
}

}  // namespace
}  // namespace mg
