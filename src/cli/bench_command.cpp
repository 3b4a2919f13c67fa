// motiongraph bench distance [INPUT...]: the distance stage measured in one run against
//  - the three plain BLAS products it needs (same N, P, tiles and threads): the ceiling;
//  - the pruned stage (graph/pruned_candidates.h) at the --max-threshold ceiling: its time,
//    the share of tiles and pairs it computed, and whether its minima equal the exhaustive
//    stage's (run again with the pruned stage's tile side when --tile is another);
//  - the pair-by-pair reference (timed on a random sample of pairs, scaled to all N^2 pairs).
// Prints the times and their ratios. Speed is measured here, never asserted in tests.
#include <algorithm>
#include <chrono>
#include <iterator>
#include <random>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "cli/bench_synthesis.h"
#include "cli/commands.h"
#include "motiongraph/core/file_extension.h"
#include "motiongraph/database/database_loader.h"
#include "motiongraph/graph/candidates.h"
#include "motiongraph/graph/pruned_candidates.h"
#include "motiongraph/graph/threshold_choice.h"
#include "motiongraph/metric/frame_features.h"
#include "motiongraph/metric/reference_distance.h"

namespace mg::cli {

namespace {

struct BenchOptions {
  std::string what;
  std::vector<std::string> inputs;
  double fps = 120.0;
  int max_frames = 0;
  int reference_pairs = 20000;
  int repeat = 1;
  double max_rms_cm = ThresholdChoiceSettings{}.max_rms_cm;
  int pruned_tile_frames = 0;
  DistanceSettings distance;
};

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const size_t m = values.size() / 2;
  return values.size() % 2 == 1 ? values[m] : 0.5 * (values[m - 1] + values[m]);
}

int run_bench(const BenchOptions& o) {
  if (o.what == "synthesis") {
    if (o.inputs.size() != 1 || lower_extension(o.inputs[0]) != ".mgraph") {
      return fail(Error{"", 0, "bench synthesis needs one GRAPH.mgraph"});
    }
    return run_synthesis_bench(o.inputs[0]);
  }
  if (o.what != "distance") {
    return fail(Error{"", 0, fmt::format("unknown benchmark '{}' (try: distance, synthesis)", o.what)});
  }
  DatabaseSettings settings;
  settings.fps = o.fps;
  settings.prefer_manifest_fps = false;
  settings.cmu_tags = false;
  settings.mirror = DatabaseSettings::Mirroring::kOff;  // the library's frames as given
  auto db = load_database(o.inputs, settings);
  if (!db) return fail(db.error());
  if (o.max_frames > 0) {
    // Keep whole clips up to the frame budget.
    size_t keep = 0;
    while (keep < db->clips.size() && db->clips[keep].first_frame + db->clips[keep].frame_count <= o.max_frames) ++keep;
    db->clips.resize(std::max<size_t>(keep, 1));
  }
  auto layout = make_cloud_layout(db->skeletons.front(), {});
  if (!layout) return fail(layout.error());
  auto features = make_frame_features(*db, *layout, o.distance);
  if (!features) return fail(features.error());
  const int n = features->frames;
  fmt::print("distance stage benchmark: {} frames ({} clips at {:g} fps), {} points, window {}, tiles {}, threads {}\n",
             n, db->clips.size(), db->fps, features->points, features->window, o.distance.tile_frames,
             o.distance.threads == 0 ? std::string("all cores") : std::to_string(o.distance.threads));

  // Products, stage and pruned stage alternate, so that all see the same load; medians over
  // the runs. The pruned stage runs the exhaustive stage's tiles (at its own tile side), so the
  // exhaustive stage at that side is run too: their minima must be the same pairs.
  const double ceiling = distance_of_rms_cm(o.max_rms_cm, *features);
  PrunedSearchSettings pruned_settings;
  pruned_settings.threads = o.distance.threads;
  pruned_settings.tile_frames = o.pruned_tile_frames;
  DistanceSettings same_tiles = o.distance;
  same_tiles.tile_frames = pruned_settings.tile_for(features->window);
  const bool other_side = same_tiles.tile_frames != o.distance.tile_frames;
  std::vector<double> products_runs, stage_runs, ratios, pruned_runs, speedups, same_side_runs;
  Result<CandidateSearch> search = Error{"", 0, "not run"};
  Result<CandidateSearch> pruned = Error{"", 0, "not run"};
  Result<CandidateSearch> same_side = Error{"", 0, "not run"};
  PrunedSearchStatistics pruned_stats;
  for (int run = 0; run < o.repeat; ++run) {
    products_runs.push_back(time_plain_products(*features, o.distance));
    auto start = std::chrono::steady_clock::now();
    search = find_candidates(*features, o.distance, {});
    stage_runs.push_back(seconds_since(start));
    if (!search) return fail(search.error());
    ratios.push_back(stage_runs.back() / products_runs.back());
    start = std::chrono::steady_clock::now();
    pruned = find_candidates_pruned(*features, ceiling, {}, pruned_settings, &pruned_stats);
    pruned_runs.push_back(seconds_since(start));
    if (!pruned) return fail(pruned.error());
    speedups.push_back(stage_runs.back() / pruned_runs.back());
    if (other_side) {
      start = std::chrono::steady_clock::now();
      same_side = find_candidates(*features, same_tiles, {});
      same_side_runs.push_back(seconds_since(start));
      if (!same_side) return fail(same_side.error());
    }
  }
  const double products_s = median(products_runs);
  const double stage_s = median(stage_runs);
  const double pruned_s = median(pruned_runs);
  // The minima at or below the ceiling, compared pair by pair.
  auto below_ceiling = [ceiling](const CandidateSearch& c) {
    std::vector<std::pair<int, int>> minima;
    for (const Transition& t : c.minima) {
      if (t.distance <= ceiling) minima.emplace_back(t.from_frame, t.to_frame);
    }
    return minima;
  };
  auto in_one_only = [](const std::vector<std::pair<int, int>>& x, const std::vector<std::pair<int, int>>& y) {
    std::vector<std::pair<int, int>> only_one;
    std::set_symmetric_difference(x.begin(), x.end(), y.begin(), y.end(), std::back_inserter(only_one));
    return only_one.size();
  };
  const auto exhaustive_minima = below_ceiling(*search), pruned_minima = below_ceiling(*pruned);
  const size_t differ_default = in_one_only(exhaustive_minima, pruned_minima);
  const size_t differ_same = other_side ? in_one_only(below_ceiling(*same_side), pruned_minima) : differ_default;

  // The reference on random defined pairs, from double clouds of every frame.
  const std::vector<Vec3> clouds = database_clouds(*db, *layout);
  std::mt19937 rng(1);
  std::uniform_int_distribution<int> frame(0, n - 1);
  std::vector<std::pair<int, int>> pairs;
  while (static_cast<int>(pairs.size()) < o.reference_pairs) {
    const int a = frame(rng), b = frame(rng);
    if (features->can_leave[a] && features->can_arrive[b]) pairs.emplace_back(a, b);
  }
  auto start = std::chrono::steady_clock::now();
  double sink = 0.0;
  for (const auto& [a, b] : pairs) {
    sink += reference_distance(clouds, features->points, features->point_weights, features->taper, a, b).distance;
  }
  const double reference_per_pair = seconds_since(start) / static_cast<double>(pairs.size());
  const double reference_s = reference_per_pair * static_cast<double>(n) * n;
  const double pairs_total = static_cast<double>(n) * n;
  const std::string runs = o.repeat > 1 ? fmt::format(" (median of {} runs)", o.repeat) : std::string();
  fmt::print("plain BLAS products (3 sgemm per tile): {:8.3f} s{}\n", products_s, runs);
  fmt::print("distance stage (products, diagonal sums, closed form, minima, histogram): {:8.3f} s  "
             "= {:.2f}x the plain products; {:.1f} M pairs/s\n",
             stage_s, median(ratios), pairs_total / stage_s / 1e6);
  if (o.repeat > 1) {
    fmt::print("ratio per run: {:.2f}\n", fmt::join(ratios, " "));
  }
  fmt::print("pair-by-pair reference, one thread ({} random pairs, {:.2f} us/pair): {:.1f} s for all {} pairs "
             "= {:.0f}x the distance stage\n",
             pairs.size(), reference_per_pair * 1e6, reference_s, static_cast<long long>(pairs_total), reference_s / stage_s);
  fmt::print("local minima: {} (checksum {:.3g})\n", search->minima.size(), sink);
  fmt::print("pruned stage at the {:g} cm ceiling (D {:.4g}), tiles of {}: {:8.3f} s = {:.2f}x faster than the "
             "distance stage (embedding {:.3f} s, tile search {:.3f} s, tiles {:.3f} s)\n",
             o.max_rms_cm, ceiling, pruned_stats.tile_frames, pruned_s, median(speedups), pruned_stats.embedding_seconds,
             pruned_stats.search_seconds, pruned_stats.exact_seconds);
  if (o.repeat > 1) fmt::print("speed-up per run: {:.2f}\n", fmt::join(speedups, " "));
  if (other_side) {
    fmt::print("distance stage with the pruned stage's tiles of {}: {:8.3f} s = {:.2f}x the pruned stage's time\n",
               same_tiles.tile_frames, median(same_side_runs), median(same_side_runs) / pruned_s);
  }
  fmt::print("pruned stage: {} of {} tiles, D of {:.2f} % of the {} pairs; {} minima at or below the ceiling, "
             "exhaustive {}; in one only: {} against the same tiles, {} against tiles of {}\n",
             pruned_stats.tiles_computed, pruned_stats.tiles,
             100.0 * static_cast<double>(pruned_stats.computed_pairs) / pairs_total,
             static_cast<long long>(pairs_total), pruned_minima.size(), exhaustive_minima.size(), differ_same,
             differ_default, o.distance.tile_frames);
  return 0;
}

}  // namespace

Command add_bench_command(CLI::App& app) {
  auto o = std::make_shared<BenchOptions>();
  CLI::App* sub = app.add_subcommand("bench", "Measure a stage against its baselines in one run and print ratios "
                                              "(benchmarks: distance; synthesis GRAPH.mgraph: path synthesis, its tag "
                                              "lookahead and the controller).");
  sub->add_option("WHAT", o->what, "The benchmark: distance or synthesis")->required();
  sub->add_option("INPUT", o->inputs, "Database inputs (folders, clips, manifests); default: data/cmu/16")
      ->default_val(std::vector<std::string>{"data/cmu/16"});
  sub->add_option("--fps", o->fps, "Database frame rate")->capture_default_str();
  sub->add_option("--max-frames", o->max_frames, "Use whole clips up to this many frames (0: all)");
  sub->add_option("--reference-pairs", o->reference_pairs, "Random pairs to time the reference on")
      ->capture_default_str()
      ->check(CLI::Range(100, 10000000));
  sub->add_option("--repeat", o->repeat, "Measure products and stage this many times each, alternating; print medians")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000));
  sub->add_option("--max-threshold", o->max_rms_cm,
                  "The pruned stage's ceiling, an RMS point distance over the window in cm (build's --max-threshold)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  sub->add_option("--tile", o->distance.tile_frames, "Tile side in frames")->capture_default_str();
  sub->add_option("--pruned-tile", o->pruned_tile_frames,
                  "The pruned stage's tile side in frames (0: chosen from the window)")
      ->capture_default_str()
      ->check(CLI::Range(0, 16384));
  sub->add_option("--threads", o->distance.threads, "Worker threads (0: one per core)")->capture_default_str();
  return {sub, [o] { return run_bench(*o); }};
}

}  // namespace mg::cli
