#include "motiongraph/motion/clip_doubts.h"

#include <cmath>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "motiongraph/motion/forward_kinematics.h"
#include "motiongraph/motion/length_unit.h"
#include "motion/walker.h"
#include "test_data.h"

namespace mg {
namespace {

bool has(const ClipDoubts& doubts, const std::string& words) {
  for (const std::string& d : doubts.phrases()) {
    if (d.find(words) != std::string::npos) return true;
  }
  return false;
}

// Two joints per frame: one at `low + wobble`, one 1.5 m above it.
std::vector<Vec3> figure(int frames, double low, double wobble) {
  std::vector<Vec3> p;
  for (int f = 0; f < frames; ++f) {
    const double y = low + wobble * ((f % 10) / 9.0);
    p.emplace_back(0.1 * f, y, 0.0);
    p.emplace_back(0.1 * f, y + 1.5, 0.0);
  }
  return p;
}

TEST(ClipDoubts, AFigureOffTheFloorIsNamedWithItsLowestJointsHeights) {
  const std::vector<ContactMask> planted(100, contact_bit(FootSide::kLeft, FootPart::kToe));
  EXPECT_TRUE(clip_doubts(figure(100, 0.0, 0.1), 2, 30.0, planted).empty());
  EXPECT_TRUE(clip_doubts(figure(100, -0.2, 0.1), 2, 30.0, planted).empty());  // within 0.25 m
  // Lowest joint from -0.80 to -0.70 m: the 2 % and 98 % quantiles of each frame's lowest.
  const auto below = clip_doubts(figure(100, -0.8, 0.1), 2, 30.0, planted);
  ASSERT_EQ(below.floor.size(), 1u);
  EXPECT_EQ(below.floor[0], "its lowest joint is 0.70-0.80 m below the floor (y = 0)");
  const auto above = clip_doubts(figure(100, 0.5, 0.1), 2, 30.0, planted);
  ASSERT_EQ(above.floor.size(), 1u);
  EXPECT_EQ(above.floor[0], "its lowest joint stays 0.50-0.60 m above the floor (y = 0)");
}

TEST(ClipDoubts, FeetThatNeverRestAreNamedInClipsOfASecondOrMore) {
  const std::vector<Vec3> p = figure(60, 0.0, 0.05);
  const std::vector<ContactMask> never(60, 0);
  EXPECT_TRUE(has(clip_doubts(p, 2, 30.0, never), "no foot rests on the floor in any frame"));
  EXPECT_TRUE(clip_doubts(p, 2, 90.0, never).empty());  // 0.67 s: too short to judge
  EXPECT_TRUE(clip_doubts(p, 2, 30.0, {}).empty());     // feet unknown: not judged
  std::vector<ContactMask> once = never;
  once[30] = contact_bit(FootSide::kRight, FootPart::kAnkle);
  EXPECT_TRUE(clip_doubts(p, 2, 30.0, once).empty());
  const auto both = clip_doubts(figure(60, -0.8, 0.1), 2, 30.0, never);
  EXPECT_EQ(both.floor.size(), 2u);
  EXPECT_EQ(clip_doubt_line("07_12", both),
            "07_12: " + both.floor[0] + ", and " + both.floor[1] +
                "; its root translation may be wrong (the distances compare clips as read, so the graph may join "
                "it to nothing)");
}

// A captured walk is on the floor with its feet planted; the same walk with its root's
// translation lowered by 0.8 m (a converter's offset) sinks below the floor by that much.
TEST(ClipDoubts, ACapturedWalkHasNoneAndItsRootLoweredSinks) {
  Clip clip = test::load_data_clip("cmu/16/16_15.amc");
  EXPECT_TRUE(clip_doubts(clip.skeleton, clip.motion).empty());
  ASSERT_GE(clip.motion.translated_count, 1);
  for (int f = 0; f < clip.motion.frame_count; ++f) clip.motion.translations(f)[0].y() -= 0.8;
  const auto doubts = clip_doubts(clip.skeleton, clip.motion);
  ASSERT_EQ(doubts.floor.size(), 1u) << clip_doubts_text(doubts);
  EXPECT_TRUE(has(doubts, "m below the floor (y = 0)")) << doubts.floor[0];
  // Planted feet are found on the clip's own floor, so they still rest: only the height is wrong.
  EXPECT_FALSE(has(doubts, "no foot rests"));
}

// A figure read in the wrong unit (a walk in metres read as centimetres, or as millimetres taken
// for metres) is named by its size alone: its floor and feet are a person's limits, not judged.
TEST(ClipDoubts, AFigureOfNoPersonsSizeIsNamedAloneByItsSize) {
  const Clip clip = test::load_data_clip("cmu/16/16_15.amc");
  const std::vector<Vec3> positions = world_positions(clip.skeleton, clip.motion);
  const int joints = clip.skeleton.joint_count();
  const auto scaled = [&](double factor) {
    std::vector<Vec3> p = positions;
    for (Vec3& v : p) v *= static_cast<float>(factor);
    return clip_doubts(p, joints, clip.motion.fps, {});
  };
  EXPECT_TRUE(scaled(1.0).empty());
  EXPECT_TRUE(scaled(1.5).empty());  // a tall person's arms swung wide
  for (const double factor : {0.01, 0.1, 4.0, 100.0, 1e30}) {
    const ClipDoubts doubts = scaled(factor);
    EXPECT_FALSE(doubts.size.empty()) << factor;
    EXPECT_TRUE(doubts.floor.empty()) << factor;  // 100 m tall: its lowest joint off the floor, unsaid
    EXPECT_NE(clip_doubts_text(doubts).find("no person's size (0.4-4 m)"), std::string::npos) << factor;
  }
  // The figure's size is its largest extent, the median over the frames: a walk of 1.7 m by 1.7.
  const ClipDoubts tall = scaled(100.0);
  EXPECT_NE(tall.size.find("its figure is 1"), std::string::npos) << tall.size;
  EXPECT_EQ(tall.phrases(), std::vector<std::string>{tall.size});
  EXPECT_EQ(scaled(0.0).size, "its joints all lie at one point (its bones have no length)");
  ClipDoubtSettings upside_down;
  upside_down.min_figure_m = 3.0;
  upside_down.max_figure_m = 2.0;
  EXPECT_FALSE(upside_down.validate());
}

}  // namespace
}  // namespace mg

namespace mg {
namespace {

// Two jumps of a figure 1.5 m tall, 0.5 and 0.4 s in the air at g, sampled at 30 fps.
struct Jumping {
  std::vector<Vec3> positions;
  std::vector<ContactMask> contacts;
};

Jumping jumping() {
  Jumping out;
  auto add = [&](double h, bool planted) {
    out.positions.emplace_back(0.0, h, 0.0);
    out.positions.emplace_back(0.0, h + 1.5, 0.0);
    out.contacts.push_back(planted ? contact_bit(FootSide::kRight, FootPart::kToe) : 0);
  };
  for (const double air : {0.5, 0.4}) {
    for (int f = 0; f < 20; ++f) add(0.0, true);
    for (int f = 1; f * (1.0 / 30.0) < air; ++f) {
      const double t = f / 30.0;
      add(9.81 * air / 2.0 * t - 0.5 * 9.81 * t * t, false);
    }
  }
  for (int f = 0; f < 20; ++f) add(0.0, true);
  return out;
}

// A clock that is not the capture's (a Frame Time of 30 fps on 120 fps frames) is named with
// the rate the file more likely has; at its own clock, or within 1.5x of it, nothing is said.
TEST(ClipDoubts, FlightsFallingAtASixteenthOfGravityNameTheLikelyFrameRate) {
  const Jumping j = jumping();
  EXPECT_TRUE(clip_doubts(j.positions, 2, 30.0, j.contacts).empty());
  EXPECT_TRUE(clip_doubts(j.positions, 2, 25.0, j.contacts).empty());  // 1.2x slow: within
  const ClipDoubts slow = clip_doubts(j.positions, 2, 7.5, j.contacts, {}, ClipClock{7.5, false});
  EXPECT_TRUE(slow.floor.empty());
  EXPECT_EQ(slow.clock,
            "its flights fall at 0.61 m/s^2, not 9.81: it plays about 4.0x slower than it was captured; its frame "
            "rate as read, 7.5 fps, is likely about 4.0 times that (--input-fps; a manifest's input_fps for one clip)");
  EXPECT_EQ(slow.phrases(), std::vector<std::string>{slow.clock});
  EXPECT_EQ(clip_doubts_text(slow), slow.clock);
  EXPECT_EQ(clip_doubt_line("16_01", slow), "16_01: " + slow.clock);  // no word on distances
  // The rate read unknown (a graph file's clips keep none): how many times it.
  const ClipDoubts loaded = clip_doubts(j.positions, 2, 7.5, j.contacts);
  EXPECT_NE(loaded.clock.find("its frame rate is likely about 4.0 times the one read (--input-fps"), std::string::npos)
      << loaded.clock;
  // Keys timed in seconds (glTF, FBX): --input-fps samples them and cannot help.
  const ClipDoubts keyed = clip_doubts(j.positions, 2, 7.5, j.contacts, {}, ClipClock{7.5, true});
  EXPECT_NE(keyed.clock.find("its keys' times look about 4.0 times what they should (export it again"),
            std::string::npos)
      << keyed.clock;
  EXPECT_EQ(keyed.clock.find("--input-fps"), std::string::npos) << keyed.clock;
  const ClipDoubts fast = clip_doubts(j.positions, 2, 60.0, j.contacts, {}, ClipClock{60.0, false});
  EXPECT_NE(fast.clock.find("it plays about 2.0x faster than it was captured; its frame rate as read, 60 fps, is "
                            "likely about 1/2.0 of that"),
            std::string::npos)
      << fast.clock;
  // A figure below the floor is judged by its floor alone: its contacts mean nothing.
  std::vector<Vec3> sunk = j.positions;
  for (Vec3& p : sunk) p.y() -= 0.8;
  const ClipDoubts floor = clip_doubts(sunk, 2, 7.5, j.contacts);
  EXPECT_FALSE(floor.floor.empty());
  EXPECT_TRUE(floor.clock.empty());
  ClipDoubtSettings none;
  none.max_slowdown = 1.0;
  EXPECT_FALSE(none.validate());
}

// A clip without flights is judged by its walk: the phrase names its strides and what a walk's
// of their length take.
TEST(ClipDoubts, AWalkWhoseStridesTakeFourTimesTooLongNamesTheLikelyFrameRate) {
  const test::Walker w = test::walker({});  // 1.3 m strides of 1 s at 30 fps
  EXPECT_TRUE(clip_doubts(w.positions, test::kWalkerJoints, 30.0, w.contacts, {}, {}, w.feet).empty());
  // Read at 7.5 fps its strides take 4 s; people's of 1.3 m take the time whose walk ratio is
  // kWalkRatio, 4 s / k.
  const ClipDoubts slow =
      clip_doubts(w.positions, test::kWalkerJoints, 7.5, w.contacts, {}, ClipClock{7.5, false}, w.feet);
  const double figure = figure_size(w.positions, test::kWalkerJoints);
  const double k = 1.3 / figure * 4.0 * std::sqrt(kGravityMps2 / figure) / kWalkRatio;
  ASSERT_GT(k, 3.0);
  EXPECT_EQ(slow.clock,
            fmt::format("its walking strides of 1.30 m take 4.00 s, where people's of that length take about {:.2f} "
                        "s: it plays about {:.1f}x slower than it was captured; its frame rate as read, 7.5 fps, is "
                        "likely about {:.1f} times that (--input-fps; a manifest's input_fps for one clip)",
                        4.0 / k, k, k));
  EXPECT_NEAR(slow.slowdown, k, 1e-9);
  // The feet's joints unknown: the walk is not judged.
  EXPECT_TRUE(clip_doubts(w.positions, test::kWalkerJoints, 7.5, w.contacts).empty());
}

// Where both are measured, the flights judge the clock: gravity is the surer clock.
TEST(ClipDoubts, FlightsJudgeTheClockBeforeTheWalk) {
  // The walker at 120 fps read at 30 (its strides 4x too long), then two jumps falling at g at 30 fps.
  test::Walker w = test::walker({.fps = 120.0});
  const std::vector<Vec3> last(w.positions.end() - test::kWalkerJoints, w.positions.end());
  const auto add = [&](double h, ContactMask contacts) {
    for (const Vec3& p : last) w.positions.push_back(p + Vec3(0.0, h, 0.0));
    w.contacts.push_back(contacts);
  };
  const ContactMask standing = w.contacts.back();
  for (const double air : {0.5, 0.4}) {
    for (int f = 0; f < 10; ++f) add(0.0, standing);
    for (int f = 1; f * (1.0 / 30.0) < air; ++f) {
      const double t = f / 30.0;
      add(kGravityMps2 * air / 2.0 * t - 0.5 * kGravityMps2 * t * t, 0);
    }
  }
  for (int f = 0; f < 10; ++f) add(0.0, standing);
  const ClipDoubts doubts = clip_doubts(w.positions, test::kWalkerJoints, 30.0, w.contacts, {}, {}, w.feet);
  ASSERT_TRUE(doubts.flight_fall.measured());
  EXPECT_NEAR(doubts.flight_fall.slowdown(), 1.0, 0.05);
  EXPECT_GT(doubts.walk_pace.slowdown(), 3.0);
  EXPECT_TRUE(doubts.clock.empty()) << doubts.clock;
}

}  // namespace
}  // namespace mg

namespace mg {
namespace {

// A clip whose only doubt is its clock, judged by its flights (fall) or its walk.
DoubtedClip clocked(const std::string& name, double k, bool by_flights, double read_fps = 30.0) {
  DoubtedClip c{name, {}, ClipClock{read_fps, false}};
  c.doubts.slowdown = k;
  c.doubts.clock = name + "'s clock";
  if (by_flights) c.doubts.flight_fall.fall_mps2 = kGravityMps2 / (k * k);
  return c;
}

TEST(ClipDoubts, ClipsReadAtOneRateWhoseOnlyDoubtIsTheirClockAreSaidInOneLine) {
  ClipDoubts floating;
  floating.floor = {"its lowest joint stays 0.50-0.60 m above the floor (y = 0)"};
  const std::vector<DoubtedClip> clips = {clocked("a", 4.4, true),      clocked("b", 3.6, false),
                                          {"f", floating, {}},          clocked("fast", 0.5, false),
                                          clocked("c", 4.0, false),     clocked("d", 3.9, true),
                                          clocked("e", 4.2, true, 60.0), clocked("g", 3.8, true)};
  const std::vector<std::string> lines = clip_doubt_lines(clips);
  // a, b, c, d and g (read at 30 fps, slow) in one line at the first's place, at the median of
  // their factors (3.6, 3.8, 3.9, 4.0, 4.4); the others their own.
  ASSERT_EQ(lines.size(), 4u) << fmt::format("{}", fmt::join(lines, "\n"));
  EXPECT_EQ(lines[0],
            "a, b, c and 2 more: their flights or walking strides say they play about 3.9x slower than they were "
            "captured (3.6-4.4x); their frame rate as read, 30 fps, is likely about 3.9 times that (--input-fps; a "
            "manifest's input_fps for one clip)");
  EXPECT_EQ(lines[1], clip_doubt_line("f", floating));
  EXPECT_EQ(lines[2], "fast: fast's clock");
  EXPECT_EQ(lines[3], "e: e's clock");
  // Two alike are said one by one; three, whose factors all came from flights, in one line.
  EXPECT_EQ(clip_doubt_lines(std::vector<DoubtedClip>{clocked("a", 4.0, true), clocked("b", 4.0, true)}),
            (std::vector<std::string>{"a: a's clock", "b: b's clock"}));
  const std::vector<std::string> fast = clip_doubt_lines(
      std::vector<DoubtedClip>{clocked("a", 0.5, true), clocked("b", 0.4, true), clocked("c", 0.625, true)});
  ASSERT_EQ(fast.size(), 1u);
  EXPECT_EQ(fast[0],
            "a, b, c: their flights say they play about 2.0x faster than they were captured (1.6-2.5x); their frame "
            "rate as read, 30 fps, is likely about 1/2.0 of that (--input-fps; a manifest's input_fps for one clip)");
  // Four are named all; playing fast, the factor is the median of their speed-ups (4, 4, 2, 2: 3).
  const std::vector<std::string> four = clip_doubt_lines(std::vector<DoubtedClip>{
      clocked("a", 0.25, true), clocked("b", 0.25, true), clocked("c", 0.5, true), clocked("d", 0.5, true)});
  ASSERT_EQ(four.size(), 1u);
  EXPECT_EQ(four[0].substr(0, four[0].find(';')),
            "a, b, c, d: their flights say they play about 3.0x faster than they were captured (2.0-4.0x)");
  // Keys timed in seconds: export them again; factors alike give no range.
  std::vector<DoubtedClip> keyed = {clocked("a", 4.0, false), clocked("b", 4.0, false), clocked("c", 4.0, false)};
  for (DoubtedClip& c : keyed) c.clock.keys_in_seconds = true;
  EXPECT_EQ(clip_doubt_lines(keyed)[0],
            "a, b, c: their walking strides say they play about 4.0x slower than they were captured; their keys' "
            "times look about 4.0 times what they should (export them again at the capture's rate)");
}

}  // namespace
}  // namespace mg
