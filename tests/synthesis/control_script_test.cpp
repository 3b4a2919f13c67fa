#include "motiongraph/synthesis/control_script.h"

#include <gtest/gtest.h>

#include "motiongraph/synthesis/controller.h"
#include "test_data.h"

namespace mg {
namespace {

TEST(ControlScript, LaterControlsKeepWhatTheyDoNotSay) {
  auto script = parse_control_script(R"({"duration_s": 12, "controls": [
      {"at_s": 0, "heading": "north", "tag": "walk"},
      {"at_s": 4, "heading_deg": 90},
      {"at_s": 8, "tag": "run"},
      {"at_s": 10, "heading": "west", "tag": "Any"}]})", "c.json");
  ASSERT_TRUE(script.ok()) << script.error().to_string();
  EXPECT_DOUBLE_EQ(script->duration_s, 12.0);
  EXPECT_EQ(script->at(3.9).tag, "walk");
  EXPECT_DOUBLE_EQ(script->at(3.9).bearing_deg, 0.0);
  EXPECT_DOUBLE_EQ(script->at(4.0).bearing_deg, 90.0);
  EXPECT_EQ(script->at(4.0).tag, "walk");
  EXPECT_EQ(script->at(9.0).tag, "run");
  EXPECT_DOUBLE_EQ(script->at(9.0).bearing_deg, 90.0);
  EXPECT_EQ(script->at(11.0).tag, "");
  EXPECT_DOUBLE_EQ(script->at(11.0).bearing_deg, 270.0);
}

// rest is carried on as the rest is, and a control may say only it.
TEST(ControlScript, RestIsCarriedOnUntilTakenBack) {
  auto script = parse_control_script(R"({"controls": [
      {"at_s": 0, "tag": "walk"},
      {"at_s": 3, "rest": true},
      {"at_s": 5, "heading": "east"},
      {"at_s": 7, "rest": false}]})", "c.json");
  ASSERT_TRUE(script.ok()) << script.error().to_string();
  EXPECT_FALSE(script->at(2.9).rest);
  EXPECT_TRUE(script->at(3.0).rest);
  EXPECT_EQ(script->at(3.0).tag, "walk");
  EXPECT_TRUE(script->at(6.0).rest);
  EXPECT_DOUBLE_EQ(script->at(6.0).bearing_deg, 90.0);
  EXPECT_FALSE(script->at(7.0).rest);
  EXPECT_DOUBLE_EQ(script->duration_s, 11.0);
}

TEST(ControlScript, BearingsAreCompassBearings) {
  EXPECT_LT((bearing_direction(0.0) - Vec2(0.0, -1.0)).norm(), 1e-12);   // north: -z
  EXPECT_LT((bearing_direction(90.0) - Vec2(1.0, 0.0)).norm(), 1e-12);   // east: +x
  for (double b : {0.0, 45.0, 135.0, 200.0, 359.0}) EXPECT_NEAR(direction_bearing(bearing_direction(b)), b, 1e-9);
}

TEST(ControlScript, BadInputIsOneClearError) {
  const std::vector<test::ErrorCase> cases = {
      {"JSON syntax", "{\"controls\": [\n{\"at_s\": 0,}\n]}", 2, "not valid JSON"},
      {"no controls", "{\"controls\": []}", 0, "non-empty \"controls\""},
      {"first not at 0", "{\"controls\": [{\"at_s\": 1, \"tag\": \"walk\"}]}", 0,
       "controls[0]: the first control is at 0 s (the script's start), not 1 s"},
      {"time going back",
       "{\"controls\": [{\"at_s\": 0, \"tag\": \"walk\"}, {\"at_s\": 3, \"tag\": \"run\"}, "
       "{\"at_s\": 2, \"tag\": \"walk\"}]}",
       0, "controls[2]: at_s 2 must come after the control before it (3 s)"},
      {"bad heading", "{\"controls\": [{\"at_s\": 0, \"heading\": \"up\"}]}", 0, "north, east, south or west"},
      // A bearing given as "heading": told the key that takes it.
      {"numeric heading", "{\"controls\": [{\"at_s\": 0, \"heading\": 135}]}", 0,
       "north, east, south or west (a bearing in degrees is \"heading_deg\": 135)"},
      {"bad duration", "{\"duration_s\": -1, \"controls\": [{\"at_s\": 0, \"tag\": \"walk\"}]}", 0, "duration_s"},
      // Frame counts past an int's range (a control at 1e9 s crashed steer).
      {"control past a day", "{\"controls\": [{\"at_s\": 0, \"tag\": \"walk\"}, {\"at_s\": 1e9, \"tag\": \"run\"}]}",
       0, "controls[1]: at_s 1e+09 is past a day"},
      {"duration past a day", "{\"duration_s\": 1e300, \"controls\": [{\"at_s\": 0, \"tag\": \"walk\"}]}", 0,
       "longer than a day"},
      // Mistakes that were read silently: a misspelt or unknown key (ignored), both headings (the
      // degrees won), a control after the end (never played).
      {"unknown key", "{\"controls\": [{\"at_s\": 0, \"speed\": 2}]}", 0, "controls[0]: unknown key \"speed\""},
      {"misspelt top key", "{\"duration\": 10, \"controls\": [{\"at_s\": 0, \"tag\": \"walk\"}]}", 0,
       "unknown key \"duration\""},
      {"two headings", "{\"controls\": [{\"at_s\": 0, \"heading\": \"north\", \"heading_deg\": 45}]}", 0,
       "controls[0] gives both \"heading\" and \"heading_deg\""},
      // A control that says nothing, a heading no compass gives.
      {"empty control", "{\"controls\": [{\"at_s\": 0, \"tag\": \"walk\"}, {\"at_s\": 2}]}", 0,
       "controls[1] gives no \"heading\", \"heading_deg\", \"tag\" or \"rest\": it changes nothing"},
      {"rest not a boolean", "{\"controls\": [{\"at_s\": 0, \"tag\": \"walk\"}, {\"at_s\": 2, \"rest\": \"yes\"}]}", 0,
       "controls[1]: rest must be true or false"},
      {"huge heading", "{\"controls\": [{\"at_s\": 0, \"heading_deg\": 1e300}]}", 0,
       "controls[0]: heading_deg 1e+300 is past +-36000 degrees"},
      {"control after the end",
       "{\"duration_s\": 5, \"controls\": [{\"at_s\": 0, \"tag\": \"walk\"}, {\"at_s\": 7, \"tag\": \"run\"}]}", 0,
       "controls[1] at 7 s comes at or after the script's end (\"duration_s\" 5)"},
  };
  for (const auto& c : cases) {
    auto script = parse_control_script(c.text, "c.json");
    ASSERT_FALSE(script.ok()) << c.rule;
    test::expect_error_matches(script.error(), c);
  }
}

}  // namespace
}  // namespace mg
