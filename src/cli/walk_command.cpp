// motiongraph walk GRAPH --from NODE --to NODE --cost C -o OUT: the cheapest walk between two
// nodes by branch and bound (synthesis/walk_search.h), played as motion.
#include <chrono>

#include <fmt/format.h>

#include "cli/commands.h"
#include "cli/synthesis_options.h"
#include "motiongraph/synthesis/walk_search.h"

namespace mg::cli {

namespace {

struct WalkOptions {
  SynthesisOptions common;
  int from = 0;
  int to = 0;
  std::string cost = "quality";
  std::uint64_t seed = 1;
  int min_frames = 0;
  long long max_expansions = 2000000;
};

int run_walk(const WalkOptions& o) {
  const auto begin = std::chrono::steady_clock::now();
  WalkSearchSettings settings;
  auto cost = parse_walk_cost(o.cost);
  if (!cost) return fail_usage(cost.error());
  settings.cost = *cost;
  settings.seed = o.seed;
  settings.min_frames = o.min_frames;
  settings.max_expansions = o.max_expansions;
  if (auto s = settings.validate(); !s) return fail_usage(s.error());
  if (auto s = check_output_options(o.common); !s) return fail_usage(s.error());
  auto loaded = load_for_synthesis(o.common);
  if (!loaded) return fail(loaded.error());
  const SynthesisContext& context = (*loaded)->context();
  auto result = run_walk_synthesis(context, o.from, o.to, settings, run_settings(o.common, begin));
  if (!result) return fail(result.error());
  print_warnings(result->warnings);
  const nlohmann::json& r = result->report;
  if (auto s = write_synthesis_outputs(o.common, **loaded, result->motion, result->walk, r); !s) return fail(s.error());
  fmt::print("walk {} -> {} ({} cost): {} edges, {} transitions, {} frames ({:.1f} s), cost {:.6g}, {} expansions\n",
             o.from, o.to, walk_cost_name(settings.cost), result->walk.edges.size(), r["transitions"].get<int>(),
             result->motion.frame_count, result->motion.frame_count / context.db->fps, r["cost"].get<double>(),
             r["expansions"].get<long long>());
  return 0;
}

}  // namespace

Command add_walk_command(CLI::App& app) {
  auto o = std::make_shared<WalkOptions>();
  CLI::App* sub = app.add_subcommand(
      "walk", "Find the cheapest walk between two graph nodes by branch and bound and write its motion.\n"
              "Costs: constant (1 per edge), quality (a transition's distance), random (uniform per edge),\n"
              "hybrid (random x distance). Nodes are numbered as 'inspect --nodes' lists them.");
  o->common.add_to(*sub);
  sub->add_option("--from", o->from, "Start node")->required();
  sub->add_option("--to", o->to, "End node")->required();
  sub->add_option("--cost", o->cost, "constant, quality, random or hybrid")->capture_default_str();
  sub->add_option("--seed", o->seed, "Seed of the random costs")->check(not_negative())->capture_default_str();
  sub->add_option("--min-frames", o->min_frames, "The walk plays at least this many frames")->capture_default_str();
  sub->add_option("--max-expansions", o->max_expansions, "Search budget: partial walks extended")
      ->capture_default_str();
  return {sub, [o] { return run_walk(*o); }};
}

}  // namespace mg::cli
