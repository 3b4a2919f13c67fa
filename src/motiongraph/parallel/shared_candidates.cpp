#include "motiongraph/parallel/shared_candidates.h"

#include <sys/resource.h>

#include <chrono>
#include <optional>

#include <fmt/format.h>

#include "motiongraph/core/progress.h"
#include "motiongraph/core/stop.h"
#include "motiongraph/graph/graph_file.h"
#include "motiongraph/parallel/tile_checkpoint.h"
#include "motiongraph/parallel/tile_share.h"

namespace mg {

namespace {

// What a process hands to rank 0: "P" and its part, or "E" and its error.
std::string part_message(const Result<CandidatePart>& part) {
  return part ? "P" + serialize_candidate_part(*part) : "E" + part.error().to_string();
}

// This process's share of the pending items, in chunks saved to the checkpoint (when there is
// one) as they finish, merged into one part.
Result<CandidatePart> run_share(const FrameFeatures& features, const DistanceSettings& distance,
                                const CandidateSettings& settings, const TileItems& items,
                                std::span<const long long> share, const TileCheckpoint* checkpoint,
                                const SharedSearchSettings& shared) {
  auto empty = empty_candidate_search(features, settings);
  if (!empty) return empty.error();
  CandidatePart mine;
  mine.search = std::move(*empty);
  const auto start = std::chrono::steady_clock::now();
  long long my_tiles = 0;
  for (long long item : share) my_tiles += items.tile_count(item);
  ProgressBar progress("distance", static_cast<std::uint64_t>(my_tiles), !shared.progress_bar, shared.progress_lines);
  const long long chunk_pairs = checkpoint != nullptr ? shared.checkpoint_pairs : items.frames * 1LL * items.frames;
  for (const std::vector<long long>& chunk : chunks_of(items, share, chunk_pairs)) {
    auto part = find_candidates(features, distance, settings, [&](long long, long long) { progress.advance(1); },
                                chunk, {}, shared.stop);
    if (!part) return part.error();
    if (checkpoint != nullptr) {
      CandidatePart saved;
      saved.items = chunk;
      saved.search = std::move(*part);
      saved.peak_memory_mb = peak_memory_mb();
      if (auto s = checkpoint->save(saved); !s) return s.error();
      part = std::move(saved.search);
    }
    if (auto s = merge_candidates(mine.search, *part); !s) return s.error();
    mine.items.insert(mine.items.end(), chunk.begin(), chunk.end());
  }
  progress.finish();
  mine.peak_memory_mb = peak_memory_mb();
  mine.search.tiles.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return mine;
}

// Rank 0: the parts the processes sent ("P" and a part, or "E" and an error), with the
// checkpoint's, merged into the search of all tiles; the first error otherwise.
Status merge_parts(const FrameFeatures& features, const CandidateSettings& settings,
                   std::span<const CandidatePart> restored, std::span<const std::string> messages, SharedSearch& out) {
  auto all = empty_candidate_search(features, settings);
  if (!all) return all.error();
  out.search = std::move(*all);
  for (const CandidatePart& part : restored) {
    if (auto s = merge_candidates(out.search, part.search); !s) return s;
  }
  for (size_t r = 0; r < messages.size(); ++r) {
    const std::string& message = messages[r];
    const std::string who = r == 0 ? "" : fmt::format("process {}: ", r);
    if (message.empty() || message[0] != 'P') {
      return Error{"", 0, who + (message.empty() ? std::string("no answer") : message.substr(1))};
    }
    auto part = parse_candidate_part(std::string_view(message).substr(1), fmt::format("process {}", r));
    if (!part) return part.error();
    if (auto s = merge_candidates(out.search, part->search); !s) return s;
    out.peak_memory_mb.push_back(part->peak_memory_mb);
    out.share_seconds.push_back(part->search.tiles.seconds);
  }
  return Ok{};
}

}  // namespace

Status SharedSearchSettings::validate() const {
  if (checkpoint_pairs < 1) return Error{"", 0, "checkpoint chunks must hold at least one frame pair"};
  return Ok{};
}

double peak_memory_mb() {
  rusage usage{};
  if (getrusage(RUSAGE_SELF, &usage) != 0) return 0.0;
  return static_cast<double>(usage.ru_maxrss) / 1024.0;  // Linux: kilobytes
}

Result<SharedSearch> find_candidates_shared(const FrameFeatures& features, const DistanceSettings& distance,
                                            const CandidateSettings& settings, std::uint64_t key, ProcessTeam& team,
                                            const SharedSearchSettings& shared,
                                            const std::vector<long long>* only_items,
                                            const std::vector<unsigned char>* only_sides) {
  const auto start = std::chrono::steady_clock::now();
  const bool with_checkpoint = !shared.checkpoint_folder.empty();
  Status valid = shared.validate();
  if (valid && settings.keep_matrix && (team.size() > 1 || with_checkpoint)) {
    valid = Error{"", 0, "the matrix export (--export-matrix) needs one process and no --checkpoint"};
  }
  if (valid) valid = distance.validate();
  const TileItems items = tile_items(features, distance);
  std::optional<TileCheckpoint> checkpoint;
  std::vector<CandidatePart> restored;
  if (valid && with_checkpoint) {
    checkpoint.emplace(shared.checkpoint_folder, key, items);
    auto loaded = checkpoint->load();
    if (loaded) {
      restored = std::move(*loaded);
    } else {
      valid = loaded.error();
    }
  }
  // Every process has read the checkpoint before any writes to it.
  if (auto s = team.agree(valid); !s) return s.error();

  SharedSearch out;
  out.processes = team.size();
  if (team.size() == 1 && !with_checkpoint) {
    // One process, nothing to save: the plain search (the matrix too, when asked).
    long long tiles = static_cast<long long>(items.per_side) * items.per_side;
    if (only_items != nullptr) {
      tiles = 0;
      for (size_t i = 0; i < only_items->size(); ++i) {
        tiles += only_sides != nullptr ? items.tile_count((*only_items)[i], (*only_sides)[i])
                                       : items.tile_count((*only_items)[i]);
      }
    }
    ProgressBar progress("distance", static_cast<std::uint64_t>(tiles), !shared.progress_bar, shared.progress_lines);
    // An empty subset runs nothing (find_candidates reads no items as all of them).
    auto search = only_items != nullptr && only_items->empty()
                      ? empty_candidate_search(features, settings)
                      : find_candidates(features, distance, settings, [&](long long, long long) { progress.advance(1); },
                                        only_items != nullptr ? std::span<const long long>(*only_items)
                                                              : std::span<const long long>(),
                                        only_items != nullptr && only_sides != nullptr
                                            ? std::span<const unsigned char>(*only_sides)
                                            : std::span<const unsigned char>(),
                                        shared.stop);
    progress.finish();
    if (!search) return search.error();
    out.search = std::move(*search);
    out.peak_memory_mb.push_back(peak_memory_mb());
    out.share_seconds.push_back(out.search.tiles.seconds);
    return out;
  }
  std::vector<char> done(static_cast<size_t>(items.count()), 0);
  for (const CandidatePart& part : restored) {
    out.restored_tiles += part.search.tiles.tiles;
    for (long long item : part.items) done[static_cast<size_t>(item)] = 1;
  }
  std::vector<long long> pending;
  if (only_items != nullptr) {
    for (long long item : *only_items) {
      if (!done[static_cast<size_t>(item)]) pending.push_back(item);
    }
  } else {
    for (long long item = 0; item < items.count(); ++item) {
      if (!done[static_cast<size_t>(item)]) pending.push_back(item);
    }
  }
  const std::vector<long long> share = items_of_process(items, pending, team.size(), team.rank());
  const std::vector<std::string> messages = team.gather(
      part_message(run_share(features, distance, settings, items, share, checkpoint ? &*checkpoint : nullptr, shared)));

  Status merged = Ok{};
  if (team.rank() == 0 && shared.stop.stop_requested()) {
    merged = stopped_error();  // (its own part says so only as text)
  } else if (team.rank() == 0) {
    merged = merge_parts(features, settings, restored, messages, out);
    out.search.tile_frames = distance.tile_frames;
    out.search.tiles.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  if (auto s = team.agree(merged); !s) return s.error();
  return out;
}

}  // namespace mg
