// What a user asking for a motion type is told when the graph can hardly play it: nothing for a
// type it plays for a second or more, the frames it keeps otherwise (none: "in no frame").
#include "motiongraph/evaluation/synthesis_run.h"

#include <gtest/gtest.h>

#include <string>

#include "synthesis/subject16_graph.h"

namespace mg {
namespace {

TEST(SynthesisRun, ATypeTheGraphHardlyPlaysIsSaidWithItsFrames) {
  const SynthesisContext& context = test::subject16().context();
  EXPECT_FALSE(unplayable_tag(context, "walk").has_value());
  EXPECT_FALSE(unplayable_tag(context, "swim").has_value());  // unknown: an error elsewhere
  int said = 0;
  for (const std::string& tag : context.db->tag_names) {
    const int frames = graph_frames_with(context, *context.tag_mask(tag));
    const auto why = unplayable_tag(context, tag);
    if (frames >= context.db->fps) {
      EXPECT_FALSE(why.has_value()) << tag;
      continue;
    }
    ASSERT_TRUE(why.has_value()) << tag;
    ++said;
    const std::string want = frames == 0 ? "'" + tag + "', which the graph plays in no frame"
                                         : "'" + tag + "', which the graph plays in only " + std::to_string(frames) +
                                               " frame";
    EXPECT_EQ(why->rfind(want, 0), 0u) << *why;
  }
  EXPECT_GE(said, 1);  // subject 16's stop: the standing ends of clips, where nothing leads on
}

}  // namespace
}  // namespace mg
