// libFuzzer target for the graph file reader (.mgraph) behind its checksum: the input is taken
// as a graph file, and its payload (all after the 25-byte header, or all of it when it does not
// start with the magic) is framed again with the right size and CRC-32, so that the fuzzer
// reaches the payload's parser (settings, database, skeletons, motion, contacts, candidates,
// graph) instead of stopping at a checksum mismatch. It is read both whole and as synthesis
// reads it (without the candidate minima); a file that parses is written again, must read
// again, and then writes the same bytes (the first writing may normalise: padding, NaN bits). Errors are expected results; the fuzzer looks for crashes, hangs, leaks and
// sanitizer reports. Run it with scripts/fuzz.sh.
//
// Seeds: with MOTIONGRAPH_FUZZ_GRAPH_SEED=FILE and MOTIONGRAPH_FUZZ_CLIPS=A.amc,B.amc (a
// skeleton beside them), the target builds a small graph of those clips, writes it to FILE and
// exits (scripts/fuzz.sh does this before fuzzing).
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include <zlib.h>

#include "motiongraph/graph/graph_file.h"
#include "motiongraph/io/file.h"
#include "motiongraph/pipeline/build_graph.h"

namespace {

constexpr std::string_view kMagic("MGRAPH\r\n\x1a", 9);
constexpr size_t kHeader = 9 + 4 + 8 + 4;  // magic, version, payload size, CRC-32

void check(bool condition) {
  if (!condition) std::abort();
}

template <class T>
void append(std::string& out, T value) {
  out.append(reinterpret_cast<const char*>(&value), sizeof(T));
}

std::string framed(std::string_view payload) {
  std::string out(kMagic);
  append<std::uint32_t>(out, mg::kGraphFileVersion);
  append<std::uint64_t>(out, payload.size());
  uLong crc = crc32(0L, Z_NULL, 0);
  crc = crc32(crc, reinterpret_cast<const Bytef*>(payload.data()), static_cast<uInt>(payload.size()));
  append<std::uint32_t>(out, static_cast<std::uint32_t>(crc));
  out.append(payload);
  return out;
}

void write_seed(const char* path, const char* clips) {
  std::vector<std::string> inputs;
  std::stringstream list(clips);
  for (std::string clip; std::getline(list, clip, ',');) inputs.push_back(clip);
  mg::BuildSettings settings;
  settings.threshold_mode = mg::ThresholdMode::kRmsCm;
  settings.threshold_value = 6.0;
  settings.find_cmu_index = false;
  auto built = mg::build_graph(inputs, settings);
  check(built.ok() && built->graph_status.ok());
  check(mg::write_file_atomic(path, mg::serialize_graph_file(built->file)).ok());
  std::exit(0);
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  const char* seed = std::getenv("MOTIONGRAPH_FUZZ_GRAPH_SEED");
  const char* clips = std::getenv("MOTIONGRAPH_FUZZ_CLIPS");
  if (seed != nullptr && clips != nullptr) write_seed(seed, clips);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string_view input(reinterpret_cast<const char*>(data), size);
  const bool whole = input.size() >= kHeader && input.substr(0, kMagic.size()) == kMagic;
  const std::string bytes = framed(whole ? input.substr(kHeader) : input);
  auto file = mg::parse_graph_file(bytes, "fuzz.mgraph");
  auto lean = mg::parse_graph_file(bytes, "fuzz.mgraph", mg::GraphReadOptions{.candidate_minima = false});
  check(file.ok() == lean.ok());
  if (!file.ok()) return 0;
  check(lean->candidates.minima.empty());
  const std::string written = mg::serialize_graph_file(*file);
  auto again = mg::parse_graph_file(written, "again.mgraph");
  check(again.ok());
  check(mg::serialize_graph_file(*again) == written);
  return 0;
}
