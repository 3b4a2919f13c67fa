#include "motiongraph/core/text.h"

#include <gtest/gtest.h>

#include <random>
#include <string>

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

// A byte-order mark (Windows tools write one) is skipped; a text whose lines end with CR alone
// (classic Mac OS) is read line by line, and one with LF keeps a stray CR as a separator.
TEST(LineReader, AByteOrderMarkAndLinesEndedByCarriageReturnsAlone) {
  LineReader marked("\xEF\xBB\xBFHIERARCHY\nROOT x", "m.bvh");
  EXPECT_EQ(marked.next(), "HIERARCHY");
  EXPECT_EQ(marked.next(), "ROOT x");
  LineReader mac("HIERARCHY\rROOT x\r\r{\r", "mac.bvh");
  EXPECT_EQ(mac.next(), "HIERARCHY");
  EXPECT_EQ(mac.next_tokens().size(), 2u);
  EXPECT_EQ(mac.next_tokens().at(0), "{");
  EXPECT_EQ(mac.line_number(), 4);
  EXPECT_FALSE(mac.next().has_value());
  LineReader mixed("a\rb\r\r\nc\n", "mixed.txt");
  EXPECT_EQ(mixed.next_tokens().size(), 2u);  // "a\rb\r": CR a separator where lines end with LF
  EXPECT_EQ(mixed.next(), "c");
  EXPECT_EQ(mixed.line_number(), 2);
}

TEST(Quoted, ShortPrintableTokensAreShownAsThey) {
  EXPECT_EQ(quoted("HIERARCHY"), "'HIERARCHY'");
  EXPECT_EQ(quoted(""), "''");
  EXPECT_EQ(quoted("Gelenk_Hüfte"), "'Gelenk_Hüfte'");  // well-formed UTF-8 stays readable
}

TEST(Quoted, ControlAndNonUtf8BytesAreEscaped) {
  EXPECT_EQ(quoted(std::string_view("a\0b", 3)), "'a\\x00b'");
  EXPECT_EQ(quoted("\x7f\x1b[2J"), "'\\x7f\\x1b[2J'");
  EXPECT_EQ(quoted("x\ty\r\n"), "'x\\ty\\r\\n'");
  EXPECT_EQ(quoted("\xff\xfe"), "'\\xff\\xfe'");
  EXPECT_EQ(quoted("\xc3"), "'\\xc3'");              // a sequence cut short
  EXPECT_EQ(quoted("\xc0\xaf"), "'\\xc0\\xaf'");      // overlong form of '/'
  EXPECT_EQ(quoted("\xed\xa0\x80"), "'\\xed\\xa0\\x80'");  // a UTF-16 surrogate
}

TEST(Quoted, LongTokensAreCutAfterFortyCharacters) {
  const std::string long_token(100, 'x');
  EXPECT_EQ(mg::quoted(long_token), "'" + std::string(40, 'x') + "...'");
  EXPECT_EQ(mg::quoted(std::string(40, 'x')), "'" + std::string(40, 'x') + "'");
}

// Property: whatever the bytes (a binary file's first token), the message has no control byte
// and no byte outside well-formed UTF-8, and stays short.
TEST(Quoted, AnyBytesGiveAShortPrintableMessage) {
  std::mt19937 random(12345);
  for (int trial = 0; trial < 2000; ++trial) {
    std::string bytes(random() % 300, '\0');
    for (char& c : bytes) c = static_cast<char>(random() & 0xff);
    const std::string shown = mg::quoted(bytes);  // (unqualified, a std::string finds std::quoted too)
    EXPECT_LE(shown.size(), 2 + 40 * 4 + 3u);
    for (size_t i = 0; i < shown.size(); ++i) {
      const auto c = static_cast<unsigned char>(shown[i]);
      ASSERT_FALSE(c < 0x20 || c == 0x7f) << "raw control byte in " << shown;
    }
    // Re-quoting the message leaves its bytes alone but for the quotes: nothing left to escape.
    const std::string inner = shown.substr(1, shown.size() - 2);
    if (inner.size() <= 40) {
      EXPECT_EQ(mg::quoted(inner), "'" + inner + "'") << "unescaped bytes in " << shown;
    }
  }
}

TEST(AsciiLetters, OnlyTheTwentySixLettersEachWay) {
  int upper = 0, lower = 0;
  for (int b = 0; b < 256; ++b) {
    const char c = static_cast<char>(b);
    upper += is_ascii_upper(c);
    lower += is_ascii_lower(c);
    EXPECT_EQ(is_ascii_letter(c), is_ascii_upper(c) || is_ascii_lower(c)) << b;
    EXPECT_FALSE(is_ascii_upper(c) && is_ascii_lower(c)) << b;
  }
  EXPECT_EQ(upper, 26);
  EXPECT_EQ(lower, 26);
  EXPECT_TRUE(is_ascii_upper('A') && is_ascii_upper('Z') && is_ascii_lower('a') && is_ascii_lower('z'));
  EXPECT_FALSE(is_ascii_letter('@') || is_ascii_letter('[') || is_ascii_letter('`') || is_ascii_letter('{'));
  EXPECT_FALSE(is_ascii_letter(static_cast<char>(0xE9)));  // Latin-1 e acute: a byte of a name, no letter here
}

TEST(AsciiDigits, TenDigitsAndTextOfThemOnly) {
  int digits = 0;
  for (int b = 0; b < 256; ++b) digits += is_ascii_digit(static_cast<char>(b));
  EXPECT_EQ(digits, 10);
  EXPECT_TRUE(is_ascii_digit('0') && is_ascii_digit('9'));
  EXPECT_FALSE(is_ascii_digit('/') || is_ascii_digit(':'));
  EXPECT_TRUE(is_ascii_digits("0") && is_ascii_digits("0123456789"));
  for (const char* text : {"", "+5", "-1", "0x10", "12 ", " 12", "1.5", "1e3", "12, 13"}) {
    EXPECT_FALSE(is_ascii_digits(text)) << text;
  }
}

}  // namespace
}  // namespace mg
