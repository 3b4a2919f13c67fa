// A Google Benchmark console reporter that also prints, after the usual table, the time of
// each benchmark as a multiple of its baseline's (both measured in the same run).
#pragma once

#include <benchmark/benchmark.h>

#include <cstdio>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace mg::bench {

class RatioReporter : public benchmark::ConsoleReporter {
 public:
  // (benchmark, baseline) names.
  explicit RatioReporter(std::vector<std::pair<std::string, std::string>> pairs) : pairs_(std::move(pairs)) {}

  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& run : runs) seconds_[run.benchmark_name()] = run.GetAdjustedRealTime();
    ConsoleReporter::ReportRuns(runs);
  }
  void Finalize() override {
    ConsoleReporter::Finalize();
    for (const auto& [name, baseline] : pairs_) {
      if (seconds_.count(name) && seconds_.count(baseline)) {
        std::printf("%-22s %.2fx the time of %s\n", name.c_str(), seconds_[name] / seconds_[baseline],
                    baseline.c_str());
      }
    }
  }

 private:
  std::vector<std::pair<std::string, std::string>> pairs_;
  std::map<std::string, double> seconds_;
};

// Runs the registered benchmarks with a RatioReporter for these pairs; main() of a program.
inline int run_with_ratios(int argc, char** argv, std::vector<std::pair<std::string, std::string>> pairs) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  RatioReporter reporter(std::move(pairs));
  benchmark::RunSpecifiedBenchmarks(&reporter);
  benchmark::Shutdown();
  return 0;
}

}  // namespace mg::bench
