// The distance stage (DESIGN.md sections 3.2-3.4) against the three plain float32 BLAS
// products it needs at the same N and P (same tiles, same threads): the ceiling. The stage
// is find_candidates as `motiongraph build` runs it: products, diagonal sums, closed form,
// local minima, histogram and picture. Data: the bundled subject 16 at 120 fps (about 4900
// frames), or at 30 fps for a quick run. The goal is at most 1.5x the products' time.
#include <benchmark/benchmark.h>

#include <map>
#include <memory>
#include <stdexcept>
#include <string>

#include "motiongraph/database/database_loader.h"
#include "motiongraph/graph/candidates.h"
#include "motiongraph/metric/distance_tiles.h"
#include "motiongraph/metric/frame_features.h"
#include "ratio_reporter.h"

namespace {

struct Setup {
  mg::FrameFeatures features;
  mg::DistanceSettings distance;
};

const Setup& setup(int fps) {
  static std::map<int, std::unique_ptr<Setup>> cache;
  auto& entry = cache[fps];
  if (!entry) {
    mg::DatabaseSettings settings;
    settings.fps = fps;
    settings.prefer_manifest_fps = false;
    settings.cmu_tags = false;
    auto db = mg::load_database({std::string(MOTIONGRAPH_DATA_DIR) + "/cmu/16"}, settings);
    if (!db) throw std::runtime_error(db.error().to_string());
    auto layout = mg::make_cloud_layout(db->skeletons.front(), {});
    if (!layout) throw std::runtime_error(layout.error().to_string());
    entry = std::make_unique<Setup>();
    auto features = mg::make_frame_features(*db, *layout, entry->distance);
    if (!features) throw std::runtime_error(features.error().to_string());
    entry->features = std::move(*features);
  }
  return *entry;
}

void label(benchmark::State& state, const Setup& s) {
  const double pairs = static_cast<double>(s.features.frames) * s.features.frames;
  state.counters["pairs/s"] = benchmark::Counter(pairs, benchmark::Counter::kIsIterationInvariantRate);
  state.SetLabel(std::to_string(s.features.frames) + " frames, " + std::to_string(s.features.points) + " points, k " +
                 std::to_string(s.features.window));
}

void BM_PlainProducts(benchmark::State& state) {
  const Setup& s = setup(static_cast<int>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(mg::time_plain_products(s.features, s.distance));
  label(state, s);
}

void BM_DistanceStage(benchmark::State& state) {
  const Setup& s = setup(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    auto search = mg::find_candidates(s.features, s.distance, {});
    if (!search) throw std::runtime_error(search.error().to_string());
    benchmark::DoNotOptimize(search->minima.data());
  }
  label(state, s);
}

// Wall time: the work runs on all cores.
BENCHMARK(BM_PlainProducts)->Arg(120)->Arg(30)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_DistanceStage)->Arg(120)->Arg(30)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

int main(int argc, char** argv) {
  return mg::bench::run_with_ratios(argc, argv,
                                    {{"BM_DistanceStage/120/real_time", "BM_PlainProducts/120/real_time"},
                                     {"BM_DistanceStage/30/real_time", "BM_PlainProducts/30/real_time"}});
}
