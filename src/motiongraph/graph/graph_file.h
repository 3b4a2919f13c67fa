// The .mgraph file: everything a later command needs to walk the graph and play motion, in
// one versioned, checksummed binary (DESIGN.md section 6):
//   magic "MGRAPH\r\n\x1a", format version (u32), then the size (u64) and CRC-32 (u32) of
//   each of its two sections, then the sections:
//   1. the settings used (JSON text), the key of the inputs and distance settings, the motion
//      database (skeletons, clips with their motion at the database rate and the rate each
//      was read at, tags, foot joint
//      names and every frame's foot contacts), the candidate search but its minima (distance
//      histogram, picture), the selected transitions, the pruned graph, and the build report
//      (JSON text);
//   2. the candidate minima (so another threshold needs no distance stage). Synthesis never
//      reads them, and they are most of a large library's file: a section of their own is
//      neither checksummed nor read when it is not wanted.
// The distance cache file (.mgcache) has the same framing with one section, its own magic,
// and holds just the key and the candidate search.
// Reading rejects a wrong magic, another version, a size or checksum mismatch, and any
// inconsistency, each with a clear message; writing produces bytes (io/file.h writes them
// atomically).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "motiongraph/core/error.h"
#include "motiongraph/database/motion_database.h"
#include "motiongraph/graph/candidates.h"
#include "motiongraph/graph/motion_graph.h"
#include "motiongraph/graph/transition_selection.h"

namespace mg {

// 2: skeletons keep the static joints above a trajectory joint (motion/trajectory_joint.h).
// 3: the database's foot joint names and every frame's foot contacts (or why there are none).
// 4: the candidate minima in a section of their own, with its own size and CRC-32.
// 6: transition edges say whether they are bridges (GraphEdge::bridge).
// 7: a bridge's blend is centred on the window its D was measured on (GraphEdge::blend_lead).
// 8: foot contacts measured from each joint's resting height (motion/foot_contacts.h's local floor).
// 9: each clip's rate as read (DatabaseClip::read_fps), so that a clock's doubt names it.
constexpr std::uint32_t kGraphFileVersion = 9;

struct GraphFile {
  std::string settings_json;
  std::uint64_t input_key = 0;
  MotionDatabase database;
  CandidateSearch candidates;  // minima, histogram, window, continuation radius (no matrix)
  double threshold = 0.0;
  double threshold_quantile = 0.0;
  int locality_radius = 0;
  MotionGraph graph;
  std::string report_json;
};

// What to read of a graph file. Synthesis (walk, path, steer) needs no candidate minima, the
// bulk of a large library's file (24 bytes each: 160 MB of 214 on the 8-subject library):
// without them the file opens several times faster (their section is neither checksummed nor
// read), and candidates.minima stays empty.
struct GraphReadOptions {
  bool candidate_minima = true;
};

std::string serialize_graph_file(const GraphFile& file);
Result<GraphFile> parse_graph_file(std::string_view bytes, const std::string& file_name,
                                   const GraphReadOptions& options = {});
// Reads the file at `path` (mapped, io/file.h) and parses it (what every command and the
// studio do). Every section read is checksummed.
Result<GraphFile> load_graph_file(const std::string& path, const GraphReadOptions& options = {});

std::string serialize_distance_cache(std::uint64_t key, const CandidateSearch& candidates);
// The cached candidates, or an error (a file for other inputs or settings is an error too).
Result<CandidateSearch> parse_distance_cache(std::string_view bytes, const std::string& file_name,
                                             std::uint64_t expected_key);

// Part of a distance stage: the candidates of some work items (metric/distance_tiles.h
// TileItems, numbered for `frames` frames in tiles of `tile_frames`), as a checkpoint keeps
// them (parallel/tile_checkpoint.h) and as the processes of a job hand them to rank 0. Framed
// and checksummed like the cache (.mgtiles); the picture is stored sparse (its defined pixels).
struct CandidatePart {
  std::uint64_t key = 0;  // the build's distance cache key (pipeline/distance_cache.h)
  std::int32_t frames = 0, tile_frames = 0;
  std::vector<long long> items;
  CandidateSearch search;       // no matrix
  double peak_memory_mb = 0.0;  // of the process that made it, when it was made
};

std::string serialize_candidate_part(const CandidatePart& part);
// Fails on anything but a whole, consistent part file (whatever its key: the caller compares).
Result<CandidatePart> parse_candidate_part(std::string_view bytes, const std::string& file_name);

// A 64-bit key from bytes (two independent 32-bit checksums, CRC-32 and Adler-32, of the
// same bytes), for cache keys over inputs and settings.
std::uint64_t content_key(std::string_view bytes);

}  // namespace mg
