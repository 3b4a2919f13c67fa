#include "motiongraph/core/text.h"

#include <gtest/gtest.h>

namespace mg {
namespace {

TEST(SplitTokens, SpacesTabsAndCarriageReturns) {
  auto tokens = split_tokens(" \tOFFSET\t1.5  -2 \r");
  ASSERT_EQ(tokens.size(), 3u);
  EXPECT_EQ(tokens[0], "OFFSET");
  EXPECT_EQ(tokens[1], "1.5");
  EXPECT_EQ(tokens[2], "-2");
  EXPECT_TRUE(split_tokens(" \t\r ").empty());
}

TEST(ParseFinite, AcceptsTheFormsFoundInMocapFiles) {
  EXPECT_EQ(parse_finite("1.5"), 1.5);
  EXPECT_EQ(parse_finite("-0.0"), 0.0);
  EXPECT_EQ(parse_finite(".0083333"), 0.0083333);
  EXPECT_EQ(parse_finite("7.62852e-016"), 7.62852e-16);
  EXPECT_EQ(parse_finite("+2"), 2.0);
  EXPECT_EQ(parse_finite("1E3"), 1000.0);
}

TEST(ParseFinite, RejectsEverythingElse) {
  for (const char* bad : {"", "+", "-", "nan", "NaN", "inf", "-inf", "1e999", "1.5x", "x1", "1,5", "++1", "0x10", " 1"}) {
    EXPECT_FALSE(parse_finite(bad).has_value()) << bad;
  }
}

TEST(ParseInteger, WholeTokenOnly) {
  EXPECT_EQ(parse_integer("322"), 322);
  EXPECT_EQ(parse_integer("+7"), 7);
  EXPECT_EQ(parse_integer("-3"), -3);
  EXPECT_FALSE(parse_integer("3.0").has_value());
  EXPECT_FALSE(parse_integer("99999999999999999999999").has_value());
  EXPECT_FALSE(parse_integer("").has_value());
}

TEST(LineReader, NumbersLinesAndStripsCarriageReturns) {
  LineReader in("a\r\n\r\n  b c\nlast", "f.txt");
  EXPECT_EQ(in.next(), "a");
  EXPECT_EQ(in.line_number(), 1);
  auto tokens = in.next_tokens();
  ASSERT_EQ(tokens.size(), 2u);
  EXPECT_EQ(in.line_number(), 3);
  EXPECT_EQ(in.peek_tokens().at(0), "last");
  EXPECT_EQ(in.line_number(), 3);
  EXPECT_EQ(in.next(), "last");
  EXPECT_FALSE(in.next().has_value());
  EXPECT_EQ(in.error("bad").to_string(), "f.txt:4: bad");
}

}  // namespace
}  // namespace mg
