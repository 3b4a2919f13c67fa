#include "motiongraph/io/bvh_parser.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "test_data.h"

namespace mg {
namespace {

constexpr const char* kMiniBvh =
    "HIERARCHY\n"                                                            // 1
    "ROOT Hips\n"                                                            // 2
    "{\n"                                                                    // 3
    "\tOFFSET 0 0 0\n"                                                       // 4
    "\tCHANNELS 6 Xposition Yposition Zposition Zrotation Yrotation Xrotation\n"  // 5
    "\tJOINT Left Leg {\n"                                                   // 6
    "\t\tOFFSET 1 -1 0\n"                                                    // 7
    "\t\tCHANNELS 3 Xrotation Yrotation Zrotation\n"                         // 8
    "\t\tEnd Site\n"                                                         // 9
    "\t\t{\n"                                                                // 10
    "\t\t\tOFFSET 0 -2 0\n"                                                  // 11
    "\t\t}\n"                                                                // 12
    "\t}\n"                                                                  // 13
    "\tJOINT Spine\n"                                                        // 14
    "\t{\n"                                                                  // 15
    "\t\tOFFSET 0 1 0\n"                                                     // 16
    "\t\tCHANNELS 6 Xposition Yposition Zposition Yrotation Xrotation Zrotation\n"  // 17
    "\t\tEnd Site\n"                                                         // 18
    "\t\t{\n"                                                                // 19
    "\t\t\tOFFSET 0 1 0\n"                                                   // 20
    "\t\t}\n"                                                                // 21
    "\t}\n"                                                                  // 22
    "}\n"                                                                    // 23
    "MOTION\n"                                                               // 24
    "Frames: 2\n"                                                            // 25
    "Frame Time: .0083333\n"                                                 // 26
    "1 2 3 10 20 30 1 2 3 0 1 0 4 5 6\n"                                     // 27
    "1 2 3 10 20 30 1 2 3 0 1 0 4 5 6\n";                                    // 28

TEST(BvhParser, ReadsJointsChannelsAndFrames) {
  auto doc = parse_bvh(kMiniBvh, "mini.bvh");
  ASSERT_TRUE(doc) << doc.error().to_string();
  ASSERT_EQ(doc->joints.size(), 5u);
  EXPECT_EQ(doc->joints[1].name, "Left Leg");  // names with spaces stay whole
  EXPECT_EQ(doc->joints[2].name, "Left Leg_end");
  EXPECT_TRUE(doc->joints[2].end_site);
  EXPECT_EQ(doc->joints[4].name, "Spine_end");
  EXPECT_EQ(doc->joints[3].parent, 0);
  EXPECT_EQ(doc->joints[1].channels[0], BvhChannel::kXrotation);
  EXPECT_EQ(doc->joints[3].first_channel, 9);
  EXPECT_EQ(doc->channel_count, 15);
  EXPECT_EQ(doc->frame_count, 2);
  EXPECT_DOUBLE_EQ(doc->frame_time_s, 0.0083333);
  EXPECT_EQ(doc->values.size(), 30u);
  EXPECT_EQ(doc->values[14], 6.0);
}

TEST(BvhParser, EndSiteNamesAvoidCollisions) {
  auto doc = parse_bvh(test::replace_once(kMiniBvh, "JOINT Spine", "JOINT Left Leg_end"), "collide.bvh");
  ASSERT_TRUE(doc) << doc.error().to_string();
  EXPECT_EQ(doc->joints[2].name, "Left Leg_end2");
  EXPECT_EQ(doc->joints[3].name, "Left Leg_end");
}

TEST(BvhParser, ReadsEveryBundledFile) {
  struct Expected {
    const char* file;
    size_t joints_with_channels;
    int frames;
  };
  for (const Expected& e : {Expected{"bvh/16_01.bvh", 31, 322}, Expected{"bvh/07_01.bvh", 43, 317},
                            Expected{"bvh/07_12.bvh", 43, 264}, Expected{"bvh/131_01.bvh", 31, 994},
                            Expected{"bvh/111_36.bvh", 31, 1466}}) {
    auto doc = parse_bvh(test::read_data(e.file), e.file);
    ASSERT_TRUE(doc) << doc.error().to_string();
    size_t with_channels = 0;
    for (const auto& j : doc->joints) with_channels += j.end_site ? 0 : 1;
    EXPECT_EQ(with_channels, e.joints_with_channels) << e.file;
    EXPECT_EQ(doc->frame_count, e.frames) << e.file;
    EXPECT_EQ(doc->values.size(), static_cast<size_t>(e.frames) * doc->channel_count) << e.file;
  }
}

// The same file with a byte-order mark first (Windows tools write one), and with its lines
// ended by CR alone (classic Mac OS), reads to the same joints and values.
TEST(BvhParser, AByteOrderMarkAndCarriageReturnLinesReadTheSame) {
  const std::string text = test::read_data("bvh/16_01.bvh");
  auto plain = parse_bvh(text, "16_01.bvh");
  ASSERT_TRUE(plain) << plain.error().to_string();
  std::string mac = text;
  mac.erase(std::remove(mac.begin(), mac.end(), '\r'), mac.end());
  std::replace(mac.begin(), mac.end(), '\n', '\r');
  for (const std::string& variant : {"\xEF\xBB\xBF" + text, mac}) {
    auto doc = parse_bvh(variant, "variant.bvh");
    ASSERT_TRUE(doc) << doc.error().to_string();
    ASSERT_EQ(doc->joints.size(), plain->joints.size());
    EXPECT_EQ(doc->joints[0].name, plain->joints[0].name);
    EXPECT_EQ(doc->values, plain->values);
  }
}

// Keywords and channel names in any case, as some exporters write them ("End site",
// "zrotation") and Blender reads them; joint names as written.
TEST(BvhParser, KeywordsInAnyCaseReadTheSame) {
  std::string text = kMiniBvh;
  auto replace_all = [&text](const std::string& from, const std::string& to) {
    for (size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size())) {
      text.replace(at, from.size(), to);
    }
  };
  for (const auto& [from, to] : std::vector<std::pair<std::string, std::string>>{
           {"HIERARCHY", "hierarchy"}, {"ROOT", "Root"}, {"OFFSET", "offset"}, {"CHANNELS", "Channels"},
           {"Xposition", "XPOSITION"}, {"Yrotation", "yrotation"}, {"Zrotation", "zRotation"},
           {"End Site", "End site"}, {"JOINT", "joint"}, {"MOTION", "Motion"}, {"Frames:", "FRAMES:"},
           {"Frame Time:", "frame time:"}}) {
    replace_all(from, to);
  }
  ASSERT_EQ(text.find("JOINT"), std::string::npos);
  auto plain = parse_bvh(kMiniBvh, "mini.bvh");
  auto any_case = parse_bvh(text, "any-case.bvh");
  ASSERT_TRUE(plain) << plain.error().to_string();
  ASSERT_TRUE(any_case) << any_case.error().to_string();
  ASSERT_EQ(any_case->joints.size(), plain->joints.size());
  for (size_t j = 0; j < plain->joints.size(); ++j) {
    EXPECT_EQ(any_case->joints[j].name, plain->joints[j].name);
    EXPECT_EQ(any_case->joints[j].channels, plain->joints[j].channels);
    EXPECT_EQ(any_case->joints[j].offset, plain->joints[j].offset);
    EXPECT_EQ(any_case->joints[j].end_site, plain->joints[j].end_site);
  }
  EXPECT_EQ(any_case->frame_time_s, plain->frame_time_s);
  EXPECT_EQ(any_case->values, plain->values);
  // A word that is no keyword in any case is still refused.
  replace_all("offset", "offsets");
  EXPECT_FALSE(parse_bvh(text, "t.bvh"));
}

TEST(BvhParser, HugeFrameCountAllocatesNothing) {
  auto doc = parse_bvh(test::replace_once(kMiniBvh, "Frames: 2", "Frames: 99999999999999"), "huge.bvh");
  ASSERT_FALSE(doc);
  EXPECT_EQ(doc.error().line, 25);
  EXPECT_NE(doc.error().message.find("2 motion lines follow"), std::string::npos) << doc.error().to_string();
}

TEST(BvhParser, OneCleanErrorPerRule) {
  const std::string base = kMiniBvh;
  const std::vector<test::ErrorCase> cases = {
      {"empty", "", 0, "empty file"},
      {"no HIERARCHY", test::replace_once(base, "HIERARCHY", "HIERARCHIE"), 1, "expected 'HIERARCHY'"},
      {"no ROOT", test::replace_once(base, "ROOT Hips", "JOINT Hips"), 2, "expected 'ROOT'"},
      {"missing brace", test::replace_once(base, "\tJOINT Spine\n\t{\n", "\tJOINT Spine\n"), 15, "expected '{'"},
      {"unclosed", test::replace_once(base, "\t}\n}\n", "\t}\n"), 23, "a '}' is missing"},
      {"unknown keyword", test::replace_once(base, "\t\tOFFSET 1 -1 0", "\t\tOFSET 1 -1 0"), 7, "unexpected 'OFSET'"},
      {"offset count", test::replace_once(base, "OFFSET 1 -1 0", "OFFSET 1 -1"), 7, "needs 3 numbers"},
      {"offset number", test::replace_once(base, "OFFSET 1 -1 0", "OFFSET 1 -1 zero"), 7, "not a finite number"},
      {"no offset", test::replace_once(base, "\t\tOFFSET 1 -1 0\n", ""), 6, "no OFFSET"},
      {"channel count", test::replace_once(base, "CHANNELS 3 Xrotation", "CHANNELS 2 Xrotation"), 8, "says 2 but lists 3"},
      {"too many channels", test::replace_once(base, "CHANNELS 3 Xrotation Yrotation Zrotation",
                                    "CHANNELS 7 Xrotation Yrotation Zrotation Xposition Yposition Zposition Wrotation"), 8, "not 0 to 6"},
      {"unknown channel", test::replace_once(base, "Yrotation Zrotation\n", "Yrotation Wrotation\n"), 8, "unknown channel"},
      {"repeated channel", test::replace_once(base, "Xrotation Yrotation Zrotation", "Xrotation Xrotation Zrotation"), 8, "listed twice"},
      {"duplicate name", test::replace_once(base, "JOINT Spine", "JOINT Hips"), 14, "used twice"},
      {"end site channels", test::replace_once(base, "\t\t\tOFFSET 0 -2 0\n", "\t\t\tOFFSET 0 -2 0\n\t\t\tCHANNELS 1 Xrotation\n"), 12, "no CHANNELS"},
      {"no MOTION", test::replace_once(base, "MOTION", "MOTON"), 24, "expected 'MOTION'"},
      {"no Frames", test::replace_once(base, "Frames: 2", "Frame: 2"), 25, "Frames: N"},
      {"negative frames", test::replace_once(base, "Frames: 2", "Frames: -2"), 25, "whole number"},
      {"frame time zero", test::replace_once(base, "Frame Time: .0083333", "Frame Time: 0"), 26, "must be a positive"},
      {"frame time nan", test::replace_once(base, "Frame Time: .0083333", "Frame Time: nan"), 26, "must be a positive"},
      {"fewer lines", test::replace_once(base, "Frames: 2", "Frames: 3"), 25, "but 2 motion lines follow"},
      {"more lines", test::replace_once(base, "Frames: 2", "Frames: 1"), 28, "more motion lines"},
      {"short line", test::replace_once(base, "4 5 6\n1 2 3", "4 5\n1 2 3"), 27, "has 14 values"},
      {"non-finite value", test::replace_once(base, "10 20 30 1", "10 inf 30 1"), 27, "not a finite number"},
  };
  for (const auto& c : cases) {
    auto doc = parse_bvh(c.text, "bad.bvh");
    ASSERT_FALSE(doc) << c.rule;
    test::expect_error_matches(doc.error(), c);
  }
}

TEST(BvhParser, CrlfAndSpacesReadTheSame) {
  std::string text;
  for (char c : std::string(kMiniBvh)) {
    if (c == '\n') text += '\r';
    text += c == '\t' ? ' ' : c;
  }
  auto a = parse_bvh(kMiniBvh, "a.bvh");
  auto b = parse_bvh(text, "b.bvh");
  ASSERT_TRUE(a && b);
  EXPECT_EQ(a->values, b->values);
  EXPECT_EQ(a->joints.size(), b->joints.size());
}

}  // namespace
}  // namespace mg
