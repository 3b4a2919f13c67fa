// How fast clips are read: AMC and BVH parsing and import, and forward kinematics, on the
// bundled data. The baseline is the least any text reader must do: split every line into
// tokens and convert every number (motiongraph's own strict helpers, no validation, no
// storage). Compare the bytes/s of each parser with the baseline's in the same run.
#include <benchmark/benchmark.h>

#include <stdexcept>
#include <string>

#include "motiongraph/core/text.h"
#include "motiongraph/io/amc_parser.h"
#include "motiongraph/io/asf_parser.h"
#include "motiongraph/io/bvh_parser.h"
#include "motiongraph/io/file.h"
#include "motiongraph/motion/acclaim_import.h"
#include "motiongraph/motion/bvh_import.h"
#include "motiongraph/motion/forward_kinematics.h"
#include "ratio_reporter.h"

namespace {

std::string data(const std::string& relative) {
  auto text = mg::read_text_file(std::string(MOTIONGRAPH_DATA_DIR) + "/" + relative);
  if (!text) throw std::runtime_error(text.error().to_string());
  return *text;
}

const mg::AcclaimRig& rig() {
  static const mg::AcclaimRig kRig = *mg::build_acclaim_rig(*mg::parse_asf(data("cmu/16/16.asf"), "16.asf"));
  return kRig;
}

void tokenize_baseline(benchmark::State& state, const std::string& text) {
  for (auto _ : state) {
    double sum = 0.0;
    mg::LineReader in(text, "baseline");
    while (auto line = in.next()) {
      for (auto token : mg::split_tokens(*line)) {
        if (auto v = mg::parse_finite(token)) sum += *v;
      }
    }
    benchmark::DoNotOptimize(sum);
  }
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations() * text.size()));
}

void BM_BaselineAmcText(benchmark::State& state) { tokenize_baseline(state, data("cmu/16/16_11.amc")); }
void BM_BaselineBvhText(benchmark::State& state) { tokenize_baseline(state, data("bvh/111_36.bvh")); }

void BM_ParseAmc(benchmark::State& state) {
  const std::string text = data("cmu/16/16_11.amc");
  for (auto _ : state) {
    auto doc = mg::parse_amc(text, "16_11.amc", rig().amc_layout, true);
    benchmark::DoNotOptimize(doc.ok());
  }
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations() * text.size()));
}

void BM_ParseAndImportAmc(benchmark::State& state) {
  const std::string text = data("cmu/16/16_11.amc");
  for (auto _ : state) {
    auto doc = mg::parse_amc(text, "16_11.amc", rig().amc_layout, true);
    auto motion = mg::motion_from_amc(rig(), *doc, 120.0);
    benchmark::DoNotOptimize(motion.local_rotations.data());
  }
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations() * text.size()));
}

void BM_ParseBvh(benchmark::State& state) {
  const std::string text = data("bvh/111_36.bvh");
  for (auto _ : state) {
    auto doc = mg::parse_bvh(text, "111_36.bvh");
    benchmark::DoNotOptimize(doc.ok());
  }
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations() * text.size()));
}

void BM_ForwardKinematics(benchmark::State& state) {
  auto doc = mg::parse_amc(data("cmu/16/16_11.amc"), "16_11.amc", rig().amc_layout, true);
  const mg::Motion motion = mg::motion_from_amc(rig(), *doc, 120.0);
  for (auto _ : state) {
    auto positions = mg::world_positions(rig().skeleton, motion);
    benchmark::DoNotOptimize(positions.data());
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * motion.frame_count));
  state.SetLabel("items = frames");
}

BENCHMARK(BM_BaselineAmcText);
BENCHMARK(BM_ParseAmc);
BENCHMARK(BM_ParseAndImportAmc);
BENCHMARK(BM_BaselineBvhText);
BENCHMARK(BM_ParseBvh);
BENCHMARK(BM_ForwardKinematics);

}  // namespace

int main(int argc, char** argv) {
  return mg::bench::run_with_ratios(argc, argv,
                                    {{"BM_ParseAmc", "BM_BaselineAmcText"},
                                     {"BM_ParseAndImportAmc", "BM_BaselineAmcText"},
                                     {"BM_ParseBvh", "BM_BaselineBvhText"}});
}
