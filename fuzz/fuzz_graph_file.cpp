// libFuzzer target for the graph file reader (.mgraph) behind its checksums: the input is taken
// as a graph file, and its two sections (split where its header says, or all of the input as
// the first when it does not start with the magic) are framed again with the right sizes and
// CRC-32s, so that the fuzzer reaches the payload's parser (settings, database, skeletons,
// motion, contacts, candidates, graph, minima) instead of stopping at a checksum mismatch. It
// is read both whole and as synthesis reads it (without the minima: a file read whole is read
// lean too); a file that parses is written again, must read again, and then writes the same
// bytes (the first writing may normalise: padding, NaN bits). Errors are expected results;
// the fuzzer looks for crashes, hangs, leaks and sanitizer reports. Run it with
// scripts/fuzz.sh.
//
// Seeds: with MOTIONGRAPH_FUZZ_GRAPH_SEED=FILE and MOTIONGRAPH_FUZZ_CLIPS=A.amc,B.amc (a
// skeleton beside them), the target builds a small graph of those clips, writes it to FILE and
// exits (scripts/fuzz.sh does this before fuzzing).
#include <algorithm>
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
constexpr size_t kHeader = 9 + 4 + 2 * (8 + 4);  // magic, version, each section's size and CRC-32

void check(bool condition) {
  if (!condition) std::abort();
}

template <class T>
void append(std::string& out, T value) {
  out.append(reinterpret_cast<const char*>(&value), sizeof(T));
}

template <class T>
T read_at(std::string_view bytes, size_t at) {
  T value{};
  std::memcpy(&value, bytes.data() + at, sizeof(T));
  return value;
}

std::uint32_t crc_of(std::string_view bytes) {
  const uLong crc = crc32(crc32(0L, Z_NULL, 0), reinterpret_cast<const Bytef*>(bytes.data()),
                          static_cast<uInt>(bytes.size()));
  return static_cast<std::uint32_t>(crc);
}

// The two sections (graph_file.h) framed with their right sizes and CRCs.
std::string framed(std::string_view main, std::string_view minima) {
  std::string out(kMagic);
  append<std::uint32_t>(out, mg::kGraphFileVersion);
  for (std::string_view section : {main, minima}) {
    append<std::uint64_t>(out, section.size());
    append<std::uint32_t>(out, crc_of(section));
  }
  out.append(main);
  out.append(minima);
  return out;
}

// A whole file's payload is split where its header says (the first section's size, cut to what
// is there); any other input is the first section, with no minima.
std::string reframed(std::string_view input) {
  if (input.size() < kHeader || input.substr(0, kMagic.size()) != kMagic) return framed(input, {});
  const std::string_view payload = input.substr(kHeader);
  const auto first = static_cast<size_t>(std::min<std::uint64_t>(read_at<std::uint64_t>(input, 13), payload.size()));
  return framed(payload.substr(0, first), payload.substr(first));
}

void write_seed(const char* path, const char* clips) {
  std::vector<std::string> inputs;
  std::stringstream list(clips);
  for (std::string clip; std::getline(list, clip, ',');) inputs.push_back(clip);
  mg::BuildSettings settings;
  settings.threshold_mode = mg::ThresholdMode::kRmsCm;
  settings.threshold_value = 6.0;
  settings.database.cmu_index_beside_inputs = false;
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
  const std::string bytes = reframed(std::string_view(reinterpret_cast<const char*>(data), size));
  auto file = mg::parse_graph_file(bytes, "fuzz.mgraph");
  auto lean = mg::parse_graph_file(bytes, "fuzz.mgraph", mg::GraphReadOptions{.candidate_minima = false});
  check(lean.ok() || !file.ok());
  if (!file.ok()) return 0;
  check(lean->candidates.minima.empty());
  const std::string written = mg::serialize_graph_file(*file);
  auto again = mg::parse_graph_file(written, "again.mgraph");
  check(again.ok());
  check(mg::serialize_graph_file(*again) == written);
  return 0;
}
