#include "motiongraph/io/amc_parser.h"

#include <gtest/gtest.h>

#include "test_data.h"

namespace mg {
namespace {

const AmcLayout kLayout{{"root", "a", "b", "c"}, {6, 2, 0, 1}};

constexpr const char* kMiniAmc = R"(#!OML:ASF mini.asf
:FULLY-SPECIFIED
:DEGREES
1
root 1 2 3 10 20 30
a 5 6
c 7
2
c 8
root 1.5 2 3 10 20 30
a 5 -6
)";

TEST(AmcParser, ReadsFramesInLayoutOrder) {
  auto doc = parse_amc(kMiniAmc, "mini.amc", kLayout, false);
  ASSERT_TRUE(doc) << doc.error().to_string();
  EXPECT_TRUE(doc->angles_in_degrees);  // the header wins over the default
  EXPECT_EQ(doc->frame_count, 2);
  EXPECT_EQ(doc->values_per_frame, 9);
  const std::vector<double> expected = {1, 2, 3, 10, 20, 30, 5, 6, 7, 1.5, 2, 3, 10, 20, 30, 5, -6, 8};
  EXPECT_EQ(doc->values, expected);
}

TEST(AmcParser, RadiansHeaderAndDefault) {
  auto radians = parse_amc(test::replace_once(kMiniAmc, ":DEGREES", ":RADIANS"), "r.amc", kLayout, true);
  ASSERT_TRUE(radians);
  EXPECT_FALSE(radians->angles_in_degrees);
  auto unspecified = parse_amc(test::replace_once(kMiniAmc, ":DEGREES\n", ""), "u.amc", kLayout, false);
  ASSERT_TRUE(unspecified);
  EXPECT_FALSE(unspecified->angles_in_degrees);
}

TEST(AmcParser, CrlfAndTabs) {
  std::string text;
  for (char c : std::string(kMiniAmc)) {
    if (c == '\n') text += '\r';
    text += c == ' ' ? '\t' : c;
  }
  auto doc = parse_amc(text, "crlf.amc", kLayout, true);
  ASSERT_TRUE(doc) << doc.error().to_string();
  EXPECT_EQ(doc->frame_count, 2);
}

TEST(AmcParser, OneCleanErrorPerRule) {
  const std::string base = kMiniAmc;
  const std::vector<test::ErrorCase> cases = {
      {"unknown header", test::replace_once(base, ":DEGREES", ":GRADIANS"), 3, "unknown header"},
      {"bone before any frame", test::replace_once(base, "1\nroot", "root"), 4, "expected a frame number"},
      {"frame numbers not consecutive", test::replace_once(base, "\n2\n", "\n3\n"), 8, "must be consecutive"},
      {"frame number past a 64-bit integer", test::replace_once(base, "\n2\n", "\n99999999999999999999\n"), 8,
       "frame number '99999999999999999999' is out of range"},
      {"frame after the largest number", test::replace_once(base, "\n1\n", "\n9223372036854775807\n"), 8,
       "frame 2 follows frame 9223372036854775807"},
      {"missing bone", test::replace_once(base, "c 7\n", ""), 4, "no line for bone 'c'"},
      {"missing bone in last frame", test::replace_once(base, "a 5 -6\n", ""), 8, "no line for bone 'a'"},
      {"bone twice", test::replace_once(base, "c 7\n", "c 7\nc 7\n"), 8, "appears twice"},
      {"unknown bone", test::replace_once(base, "c 7\n", "c 7\nz 1\n"), 8, "unknown bone 'z'"},
      {"too few values", test::replace_once(base, "a 5 6", "a 5"), 6, "has 1 value, its skeleton gives it 2"},
      {"too many values", test::replace_once(base, "c 8", "c 8 9"), 9, "has 2 values"},
      {"non-finite", test::replace_once(base, "a 5 6", "a 5 inf"), 6, "not a finite number"},
      {"not a number", test::replace_once(base, "a 5 6", "a 5 six"), 6, "not a finite number"},
      {"no frames", ":FULLY-SPECIFIED\n:DEGREES\n", 0, "no frames"},
  };
  for (const auto& c : cases) {
    auto doc = parse_amc(c.text, "bad.amc", kLayout, true);
    ASSERT_FALSE(doc) << c.rule;
    test::expect_error_matches(doc.error(), c);
  }
}

}  // namespace
}  // namespace mg
