#include "motiongraph/core/json_text.h"

#include <gtest/gtest.h>

namespace mg {
namespace {

TEST(JsonText, SyntaxErrorsNameTheFileAndLine) {
  auto doc = parse_json_text("{\n  \"a\": 1,\n  \"b\": ]\n}\n", "path.json");
  ASSERT_FALSE(doc.ok());
  EXPECT_EQ(doc.error().file, "path.json");
  EXPECT_EQ(doc.error().line, 3);
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
