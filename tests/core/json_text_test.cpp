// JSON text to a document, or a clean error: never an exception, whatever the text (found by
// fuzzing the floor-path and control-script readers: a number too large for a double); and
// documents to text, whatever bytes their strings hold.
#include "motiongraph/core/json_text.h"

#include <gtest/gtest.h>

#include "motiongraph/synthesis/control_script.h"
#include "motiongraph/synthesis/floor_path.h"

namespace mg {
namespace {

TEST(JsonText, SyntaxErrorNamesTheLine) {
  auto parsed = parse_json_text("{\"a\": 1,\n \"b\": ]}", "x.json");
  ASSERT_FALSE(parsed);
  EXPECT_EQ(parsed.error().file, "x.json");
  EXPECT_EQ(parsed.error().line, 2);
}

TEST(JsonText, NumberTooLargeIsAnErrorNotAnException) {
  auto parsed = parse_json_text("{\"a\": 1,\n \"b\": 3E33333331}", "x.json");
  ASSERT_FALSE(parsed);
  EXPECT_EQ(parsed.error().line, 2);
  EXPECT_NE(parsed.error().message.find("out of range"), std::string::npos) << parsed.error().message;
  EXPECT_TRUE(parse_json_text("[1e308, -1e308, 5e-324]", "x.json"));
}

// A key twice in one object (nlohmann keeps the last: the first went unread) is an error naming
// the key and the line of its second appearance; the same key in two objects, or as a value, is
// fine.
TEST(JsonText, AKeyTwiceInOneObjectIsAnErrorAtItsSecondLine) {
  auto twice = parse_json_text("{\"duration_s\": 10,\n \"controls\": [],\n \"duration_s\": 20}", "s.json");
  ASSERT_FALSE(twice);
  EXPECT_EQ(twice.error().to_string(), "s.json:3: the key \"duration_s\" appears twice in one object");
  // Nested: the inner object's repeat, counted past the keys of that name elsewhere and the
  // values that are the same text.
  auto nested =
      parse_json_text("{\"tag\": \"at_s\", \"c\": [{\"at_s\": 0},\n{\"at_s\": 1,\n \"at_s\" : 2}]}", "s.json");
  ASSERT_FALSE(nested);
  EXPECT_EQ(nested.error().line, 3);
  EXPECT_TRUE(parse_json_text("[{\"a\": 1, \"b\": {\"a\": 2}}, {\"a\": 3}]", "x.json"));
  EXPECT_FALSE(parse_control_script("{\"controls\": [{\"at_s\": 0, \"tag\": \"walk\", \"tag\": \"run\"}]}", "c.json"));
  EXPECT_FALSE(parse_path_json("{\"points\": [[0, 0], [0, 5]], \"points\": [[0, 0], [5, 0]]}", "p.json"));
}

TEST(JsonText, PathAndControlScriptRejectHugeNumbers) {
  EXPECT_FALSE(parse_path_json("{\"points\": [[0, 0], [0, 3E33333331]]}", "path.json"));
  EXPECT_FALSE(parse_path_json("                   3E33333331   ", "path.json"));
  EXPECT_FALSE(parse_control_script("{\"controls\": [{\"at_s\": 777777777777000000137e8347070}]}", "script.json"));
}

// A Latin-1 name (0xE9, "é" in Latin-1, is not UTF-8 on its own) is written as U+FFFD instead
// of throwing, and the text parses back.
TEST(JsonText, BytesThatAreNotUtf8BecomeReplacementCharacters) {
  const nlohmann::json doc = {{"joint", std::string("Cuisse_gauche_\xe9")}, {"x", 1.5}};
  std::string text;
  ASSERT_NO_THROW(text = json_text(doc));
  auto back = parse_json_text(text, "written.json");
  ASSERT_TRUE(back.ok());
  EXPECT_EQ((*back)["joint"], "Cuisse_gauche_\xef\xbf\xbd");
  EXPECT_EQ((*back)["x"], 1.5);
  // Valid UTF-8 is kept as it is, and indentation is honoured.
  const nlohmann::json ok = {{"joint", "Épaule"}};
  EXPECT_EQ(json_text(ok), "{\"joint\":\"Épaule\"}");
  EXPECT_EQ(json_text(ok, 2), "{\n  \"joint\": \"Épaule\"\n}");
}

}  // namespace
}  // namespace mg
