// Controls turned into the controller's input: a stop the graph can hardly play is rest, and what
// the graph cannot give is said once, naming who asked.
#include "motiongraph/evaluation/steering_controls.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "motiongraph/evaluation/synthesis_run.h"
#include "synthesis/subject16_graph.h"

namespace mg {
namespace {

TEST(SteeringControls, AStopTheGraphHardlyPlaysIsRestSaidOnce) {
  const SynthesisContext& context = test::subject16().context();
  ASSERT_TRUE(unplayable_tag(context, "stop").has_value());  // the standing ends of clips
  ASSERT_FALSE(context.rest().empty());
  SteeringControls controls(context);
  auto walk = controls.input({90.0, "walk", false}, "the control at 0 s");
  ASSERT_TRUE(walk) << walk.error().to_string();
  EXPECT_EQ(walk->tag, *context.tag_mask("walk"));
  EXPECT_FALSE(walk->rest);
  EXPECT_NEAR(walk->direction.x(), 1.0, 1e-12);  // east
  EXPECT_NEAR(walk->direction.y(), 0.0, 1e-12);
  EXPECT_TRUE(controls.warnings().empty());
  for (int i = 0; i < 3; ++i) {
    auto stop = controls.input({0.0, "stop", false}, "the control at " + std::to_string(i) + " s");
    ASSERT_TRUE(stop) << stop.error().to_string();
    EXPECT_TRUE(stop->rest);
    EXPECT_EQ(stop->tag, 0u);  // any motion on the way to rest
  }
  ASSERT_EQ(controls.warnings().size(), 1u);
  const std::string& said = controls.warnings().front();
  EXPECT_EQ(said, "the control at 0 s asks for " + *unplayable_tag(context, "stop") +
                      "; the character comes to rest instead, at the end of a clip that ends standing still");
  // Asking to rest where the graph can: nothing more said.
  auto rest = controls.input({0.0, "", true}, "the control at 5 s");
  ASSERT_TRUE(rest);
  EXPECT_TRUE(rest->rest);
  EXPECT_EQ(rest->tag, 0u);
  EXPECT_EQ(controls.warnings().size(), 1u);
}

TEST(SteeringControls, RestWhereNoClipEndsStandingIsSaidOnceAndTheStopIsAType) {
  SynthesisContext nowhere = test::subject16().context();
  nowhere.set_rest({});
  SteeringControls controls(nowhere);
  auto stop = controls.input({0.0, "stop", false}, "the controller");
  ASSERT_TRUE(stop);
  // No rest to come to: the stop is asked as a type, said once as the graph hardly playing it.
  EXPECT_FALSE(stop->rest);
  EXPECT_EQ(stop->tag, *nowhere.tag_mask("stop"));
  ASSERT_EQ(controls.warnings().size(), 1u);
  EXPECT_EQ(controls.warnings()[0], "the controller asks for " + *unplayable_tag(nowhere, "stop"));
  for (int i = 0; i < 2; ++i) {
    auto rest = controls.input({0.0, "walk", true}, "the controller");
    ASSERT_TRUE(rest);
    EXPECT_TRUE(rest->rest);
  }
  ASSERT_EQ(controls.warnings().size(), 2u);
  EXPECT_EQ(controls.warnings()[1],
            "the controller asks to rest, but no clip of the graph ends standing still: the character goes on");
}

TEST(SteeringControls, AnUnknownTagOrAHeadingNotFiniteIsAnError) {
  SteeringControls controls(test::subject16().context());
  auto unknown = controls.input({0.0, "fly", false}, "the control at 2 s");
  ASSERT_FALSE(unknown);
  EXPECT_NE(unknown.error().message.find("'fly' is not a motion tag"), std::string::npos) << unknown.error().message;
  auto nan = controls.input({std::numeric_limits<double>::quiet_NaN(), "walk", false}, "the control at 3 s");
  ASSERT_FALSE(nan);
  EXPECT_NE(nan.error().message.find("the control at 3 s: the heading must be finite"), std::string::npos);
  EXPECT_TRUE(controls.warnings().empty());
}

// A tag asked in another case is the graph's tag of that name; a word of the clips' vocabulary
// that is not a tag of the graph is an error that says which tag it stands for.
TEST(SteeringControls, ATagInAnyCaseIsTheGraphsAndAWordForOneSaysWhich) {
  SteeringControls controls(test::subject16().context());
  const auto walk = controls.input({0.0, "walk", false}, "the control at 0 s");
  ASSERT_TRUE(walk) << walk.error().message;
  for (const char* asked : {"WALK", "Walk"}) {
    const auto any_case = controls.input({0.0, asked, false}, "the control at 1 s");
    ASSERT_TRUE(any_case) << any_case.error().message;
    EXPECT_EQ(any_case->tag, walk->tag) << asked;
    const auto name = test::subject16().context().tag_name(asked);
    ASSERT_TRUE(name);
    EXPECT_EQ(*name, "walk");
  }
  const auto sprint = controls.input({0.0, "sprint", false}, "the control at 2 s");
  ASSERT_FALSE(sprint);
  EXPECT_NE(sprint.error().message.find("'sprint' is not a motion tag of this graph"), std::string::npos);
  EXPECT_NE(sprint.error().message.find("; 'sprint' is a word for 'run'"), std::string::npos) << sprint.error().message;
  const auto fly = controls.input({0.0, "fly", false}, "the control at 3 s");
  ASSERT_FALSE(fly);
  EXPECT_EQ(fly.error().message.find("is a word for"), std::string::npos) << fly.error().message;
}

}  // namespace
}  // namespace mg
