#include "motiongraph/graph/graph_file.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <cstdio>
#include <cstring>
#include <functional>
#include <optional>

#include <zlib.h>

#include "motiongraph/database/database_contacts.h"
#include "motiongraph/io/file.h"
#include "test_data.h"

namespace mg {
namespace {

GraphFile sample() {
  GraphFile file;
  file.settings_json = R"({"fps": 30})";
  file.input_key = 0x0123456789abcdefULL;
  file.database = test::small_database({"cmu/16/16_35.amc", "cmu/16/16_39.amc"});
  file.database.skeleton_names = {"16.asf"};
  file.database.clips[0].read_fps = 120.0;
  file.database.clips[1].read_fps = 29.97;
  const int run = file.database.tag_index("run");
  file.database.tag_ranges.push_back({run, 0, file.database.frame_count()});
  file.database.foot_names = {"lfoot", "", "rfoot", ""};
  file.database.frame_contacts = *database_contacts(file.database, {}, file.database.foot_names);
  file.candidates.window = 10;
  file.candidates.continuation_radius = 10;
  file.candidates.minima = {{3, 50, 0.5f, 0.1f, 1.0f, -2.0f}, {7, 60, 0.25f, -0.3f, 0.0f, 4.0f}};
  file.candidates.histogram.add(0.5f);
  file.candidates.histogram.add(2.0f);
  file.candidates.picture = {1.0f, 2.0f, 3.0f, 4.0f};
  file.candidates.picture_side = 2;
  file.candidates.picture_block = 40;
  file.threshold = 0.75;
  file.threshold_quantile = 0.5;
  file.locality_radius = 5;
  file.graph.window = 10;
  file.graph.nodes = {{3, 0}, {50, 1}};
  file.graph.edges = {{0, 1, true, 0, 9}, {1, 0, true, 1, 9, true}};
  file.graph.edge_offsets = {0, 1, 2};
  file.graph.transitions = file.candidates.minima;
  file.report_json = R"({"frames": 2})";
  return file;
}

TEST(GraphFile, RoundTripIsExact) {
  const GraphFile original = sample();
  const std::string bytes = serialize_graph_file(original);
  auto read = parse_graph_file(bytes, "g.mgraph");
  ASSERT_TRUE(read) << read.error().to_string();
  EXPECT_EQ(read->settings_json, original.settings_json);
  EXPECT_EQ(read->input_key, original.input_key);
  EXPECT_EQ(read->database.clips.size(), 2u);
  EXPECT_EQ(read->database.frame_count(), original.database.frame_count());
  EXPECT_EQ(read->database.tag_names, original.database.tag_names);
  EXPECT_EQ(read->database.skeletons[0].joint_count(), original.database.skeletons[0].joint_count());
  // Each clip's rate as read, so that a clock's doubt can name it.
  EXPECT_EQ(read->database.clips[0].read_fps, 120.0);
  EXPECT_EQ(read->database.clips[1].read_fps, 29.97);
  const Motion& a = original.database.clips[1].motion;
  const Motion& b = read->database.clips[1].motion;
  ASSERT_EQ(a.frame_count, b.frame_count);
  for (size_t i = 0; i < a.local_rotations.size(); ++i) ASSERT_LT(a.local_rotations[i].angularDistance(b.local_rotations[i]), 1e-6);
  EXPECT_EQ(a.local_translations_m, b.local_translations_m);
  EXPECT_EQ(read->candidates.minima.size(), 2u);
  EXPECT_EQ(read->candidates.minima[1].z_m, 4.0f);
  EXPECT_EQ(read->candidates.histogram.total(), 2u);
  EXPECT_EQ(read->candidates.picture, original.candidates.picture);
  EXPECT_EQ(read->threshold, 0.75);
  EXPECT_EQ(read->graph.edges.size(), 2u);
  EXPECT_EQ(read->graph.edges[1].transition_index, 1);
  EXPECT_FALSE(read->graph.edges[0].bridge);
  EXPECT_TRUE(read->graph.edges[1].bridge);
  EXPECT_EQ(read->report_json, original.report_json);
  EXPECT_EQ(read->database.foot_names, original.database.foot_names);
  EXPECT_EQ(read->database.frame_contacts, original.database.frame_contacts);
  EXPECT_TRUE(read->database.contacts_error.empty());
  // Writing what was read gives the same bytes.
  EXPECT_EQ(serialize_graph_file(*read), bytes);
}

// Loading from a path is reading the file and parsing it; a missing file names its path.
TEST(GraphFile, TheSameGraphGivesTheSameBytesWhateverItsEdgesPadding) {
  GraphFile a = sample();
  GraphFile b = sample();
  // The same edges on memory filled with different bytes: only the padding differs.
  for (GraphFile* file : {&a, &b}) {
    const std::vector<GraphEdge> edges = file->graph.edges;
    std::memset(static_cast<void*>(file->graph.edges.data()), file == &a ? 0x00 : 0xab,
                edges.size() * sizeof(GraphEdge));
    for (size_t i = 0; i < edges.size(); ++i) {
      file->graph.edges[i].from_node = edges[i].from_node;
      file->graph.edges[i].to_node = edges[i].to_node;
      file->graph.edges[i].transition = edges[i].transition;
      file->graph.edges[i].transition_index = edges[i].transition_index;
      file->graph.edges[i].frame_count = edges[i].frame_count;
      file->graph.edges[i].bridge = edges[i].bridge;
      file->graph.edges[i].blend_lead = edges[i].blend_lead;
    }
  }
  EXPECT_EQ(serialize_graph_file(a), serialize_graph_file(b));
}

// Only a transition can be a bridge: a clip edge flagged as one is refused.
TEST(GraphFile, AClipEdgeFlaggedABridgeIsRefused) {
  GraphFile file = sample();
  ASSERT_TRUE(parse_graph_file(serialize_graph_file(file), "g.mgraph"));
  file.graph.edges[0].transition = false;
  file.graph.edges[0].transition_index = -1;
  ASSERT_TRUE(parse_graph_file(serialize_graph_file(file), "g.mgraph"));
  file.graph.edges[0].bridge = true;
  EXPECT_FALSE(parse_graph_file(serialize_graph_file(file), "g.mgraph"));
}

// A blend lead only on a bridge, never negative, and within the frames its blend has beyond the
// window; a bridge's lead is read back as written.
TEST(GraphFile, ABlendLeadOnlyOnABridgeWithinItsBlend) {
  GraphFile file = sample();
  GraphEdge& bridge = file.graph.edges[1];
  ASSERT_TRUE(bridge.bridge);
  bridge.frame_count = file.graph.window + 4;  // blends over window + 5 frames
  bridge.blend_lead = 5;
  auto read = parse_graph_file(serialize_graph_file(file), "g.mgraph");
  ASSERT_TRUE(read) << read.error().to_string();
  EXPECT_EQ(read->graph.edges[1].blend_lead, 5);
  bridge.blend_lead = 6;
  EXPECT_FALSE(parse_graph_file(serialize_graph_file(file), "g.mgraph"));
  bridge.blend_lead = -1;
  EXPECT_FALSE(parse_graph_file(serialize_graph_file(file), "g.mgraph"));
  bridge.blend_lead = 0;
  file.graph.edges[0].blend_lead = 1;  // not a bridge
  EXPECT_FALSE(parse_graph_file(serialize_graph_file(file), "g.mgraph"));
}

// A flag byte that is neither 0 nor 1 is no bool: refused, not read as one. The edge is found in
// the first section by its bytes and the section's CRC-32 (after the magic, the version and the
// first section's size) made right again, so that only the flag is wrong.
TEST(GraphFile, AnEdgeFlagThatIsNoBoolIsRefused) {
  GraphFile file = sample();
  const std::string bytes = serialize_graph_file(file);
  ASSERT_TRUE(parse_graph_file(bytes, "g.mgraph"));
  GraphEdge edge;
  std::memset(static_cast<void*>(&edge), 0, sizeof edge);
  edge.from_node = 1;
  edge.transition = true;
  edge.transition_index = 1;
  edge.frame_count = 9;
  edge.bridge = true;
  ASSERT_EQ(file.graph.edges[1].from_node, 1);
  ASSERT_TRUE(file.graph.edges[1].bridge);
  const std::string pattern(reinterpret_cast<const char*>(&edge), sizeof edge);
  const size_t at = bytes.find(pattern);
  ASSERT_NE(at, std::string::npos);
  EXPECT_EQ(bytes.find(pattern, at + 1), std::string::npos);
  constexpr size_t kMagic = 9, kSectionStart = kMagic + 4 + 2 * (8 + 4);
  std::uint64_t size = 0;
  std::memcpy(&size, bytes.data() + kMagic + 4, 8);
  ASSERT_GT(at, kSectionStart);
  ASSERT_LT(at, kSectionStart + size);
  for (const size_t member : {offsetof(GraphEdge, transition), offsetof(GraphEdge, bridge)}) {
    std::string broken = bytes;
    broken[at + member] = 2;
    uLong crc = crc32(0L, Z_NULL, 0);
    crc = crc32(crc, reinterpret_cast<const Bytef*>(broken.data() + kSectionStart), static_cast<uInt>(size));
    const auto crc32_value = static_cast<std::uint32_t>(crc);
    std::memcpy(broken.data() + kMagic + 4 + 8, &crc32_value, 4);
    EXPECT_FALSE(parse_graph_file(broken, "g.mgraph")) << member;
    broken[at + member] = 1;  // the same CRC fix with the byte as it was: read again
    crc = crc32(crc32(0L, Z_NULL, 0), reinterpret_cast<const Bytef*>(broken.data() + kSectionStart),
                static_cast<uInt>(size));
    const auto restored = static_cast<std::uint32_t>(crc);
    std::memcpy(broken.data() + kMagic + 4 + 8, &restored, 4);
    EXPECT_TRUE(parse_graph_file(broken, "g.mgraph")) << member;
  }
}

TEST(GraphFile, LoadsFromAPath) {
  const std::string bytes = serialize_graph_file(sample());
  const std::string path = testing::TempDir() + "load_graph_file_test.mgraph";
  ASSERT_TRUE(write_file_atomic(path, bytes).ok());
  auto loaded = load_graph_file(path);
  ASSERT_TRUE(loaded) << loaded.error().to_string();
  EXPECT_EQ(serialize_graph_file(*loaded), bytes);
  std::remove(path.c_str());
  auto missing = load_graph_file(path);
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.error().to_string().find(path), std::string::npos) << missing.error().to_string();
}

// A graph file's motion lives in one block that the database holds: it stays valid when the
// database is moved out of the file and the file is gone, and a copy of the database has its
// own (read under the sanitizers, a use after free would show here).
TEST(GraphFile, TheMotionReadOutlivesTheFileAndItsCopiesTheirOriginal) {
  const GraphFile original = sample();
  MotionDatabase moved;
  {
    auto read = parse_graph_file(serialize_graph_file(original), "g.mgraph");
    ASSERT_TRUE(read) << read.error().to_string();
    ASSERT_NE(read->database.motion_memory, nullptr);
    moved = std::move(read->database);
  }
  std::optional<MotionDatabase> copy;
  {
    const MotionDatabase source = moved;
    copy = source;
  }
  for (const MotionDatabase* db : {&moved, &*copy}) {
    ASSERT_EQ(db->clips.size(), original.database.clips.size());
    for (size_t c = 0; c < db->clips.size(); ++c) {
      const Motion& a = original.database.clips[c].motion;
      const Motion& b = db->clips[c].motion;
      ASSERT_EQ(a.local_rotations.size(), b.local_rotations.size());
      for (size_t i = 0; i < a.local_rotations.size(); ++i) {
        // Stored as float: the same to float precision.
        EXPECT_NEAR(a.local_rotations[i].w(), b.local_rotations[i].w(), 1e-7);
        EXPECT_NEAR(a.local_rotations[i].x(), b.local_rotations[i].x(), 1e-7);
      }
      EXPECT_EQ(a.local_translations_m, b.local_translations_m);
    }
  }
}

// Synthesis reads a graph without its candidate minima: everything else is read alike, a file
// cut inside the minima it skips is still refused, and damage to the minima' section (last in
// the file, checksummed on its own) is seen only by a reader that reads them.
TEST(GraphFile, ReadsWithoutTheCandidateMinima) {
  const GraphFile original = sample();
  const std::string bytes = serialize_graph_file(original);
  const GraphReadOptions lean{.candidate_minima = false};
  auto read = parse_graph_file(bytes, "g.mgraph", lean);
  ASSERT_TRUE(read) << read.error().to_string();
  EXPECT_TRUE(read->candidates.minima.empty());
  EXPECT_EQ(read->candidates.histogram.total(), 2u);
  EXPECT_EQ(read->candidates.picture, original.candidates.picture);
  read->candidates.minima = original.candidates.minima;
  EXPECT_EQ(serialize_graph_file(*read), bytes);
  const std::string path = testing::TempDir() + "lean_graph_file_test.mgraph";
  ASSERT_TRUE(write_file_atomic(path, bytes).ok());
  auto loaded = load_graph_file(path, lean);
  ASSERT_TRUE(loaded) << loaded.error().to_string();
  EXPECT_TRUE(loaded->candidates.minima.empty());
  EXPECT_EQ(loaded->graph.edges.size(), original.graph.edges.size());
  std::remove(path.c_str());
  // The minimum count says more than the payload holds: refused without reading past it.
  const std::string cut = bytes.substr(0, bytes.size() - 8);
  EXPECT_FALSE(parse_graph_file(cut, "cut.mgraph", lean));
  // The minima section: a count (u64) and 24 bytes per minimum, at the end of the file.
  const size_t minima_bytes = 8 + 24 * original.candidates.minima.size();
  std::string damaged_minima = bytes;
  damaged_minima[bytes.size() - minima_bytes / 2] ^= 0x40;
  EXPECT_TRUE(parse_graph_file(damaged_minima, "g.mgraph", lean));
  auto whole = parse_graph_file(damaged_minima, "g.mgraph");
  ASSERT_FALSE(whole);
  EXPECT_NE(whole.error().message.find("checksum mismatch"), std::string::npos) << whole.error().to_string();
  std::string damaged_graph = bytes;
  damaged_graph[bytes.size() - minima_bytes - 20] ^= 0x40;  // in the report, just before the minima
  auto lean_damaged = parse_graph_file(damaged_graph, "g.mgraph", lean);
  ASSERT_FALSE(lean_damaged);
  EXPECT_NE(lean_damaged.error().message.find("checksum mismatch"), std::string::npos);
}

// FileBytes maps the file where it can: the same bytes as reading it, an empty file and a
// folder and a missing file as read_text_file has them.
TEST(FileBytes, TheSameBytesAsReadingTheFile) {
  const std::string path = testing::TempDir() + "file_bytes_test.bin";
  std::string content(100000, '\0');
  for (size_t i = 0; i < content.size(); ++i) content[i] = static_cast<char>((i * 2654435761u) >> 13);
  ASSERT_TRUE(write_file_atomic(path, content).ok());
  {
    auto bytes = FileBytes::open(path);
    ASSERT_TRUE(bytes) << bytes.error().to_string();
    EXPECT_EQ(bytes->bytes(), content);
    FileBytes moved = std::move(*bytes);  // the bytes move with it
    EXPECT_EQ(moved.bytes(), content);
  }
  ASSERT_TRUE(write_file_atomic(path, "").ok());
  auto empty = FileBytes::open(path);
  ASSERT_TRUE(empty);
  EXPECT_TRUE(empty->bytes().empty());
  std::remove(path.c_str());
  auto missing = FileBytes::open(path);
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.error().to_string().find("cannot open"), std::string::npos);
  auto folder = FileBytes::open(testing::TempDir());
  ASSERT_FALSE(folder);
  EXPECT_NE(folder.error().to_string().find("folder"), std::string::npos);
}

TEST(GraphFile, RejectsAnythingElse) {
  const std::string bytes = serialize_graph_file(sample());
  auto expect_error = [](const std::string& data, const char* part) {
    auto read = parse_graph_file(data, "bad.mgraph");
    ASSERT_FALSE(read);
    EXPECT_EQ(read.error().file, "bad.mgraph");
    EXPECT_NE(read.error().message.find(part), std::string::npos) << read.error().to_string();
  };
  expect_error("", "not a motiongraph graph");
  expect_error("HIERARCHY\nROOT x", "not a motiongraph graph");
  expect_error(bytes.substr(0, bytes.size() - 1), "truncated: ");
  expect_error(bytes + "extra", "longer than its header says");
  expect_error(bytes.substr(0, 12), "truncated header");
  std::string flipped = bytes;
  flipped[bytes.size() / 2] ^= 0x40;
  expect_error(flipped, "checksum mismatch");
  std::string other_version = bytes;
  other_version[9] = static_cast<char>(kGraphFileVersion + 1);  // the version follows the 9-byte magic
  expect_error(other_version, fmt::format("version {}, a newer motiongraph's; this one reads version {}: open it with the "
                                          "motiongraph that wrote it",
                                          kGraphFileVersion + 1, kGraphFileVersion)
                                  .c_str());
  other_version[9] = static_cast<char>(kGraphFileVersion - 1);
  expect_error(other_version, fmt::format("version {}, an older motiongraph's; this one reads version {}: build it again",
                                          kGraphFileVersion - 1, kGraphFileVersion)
                                  .c_str());
  // Contacts for some frames only, contacts beside a reason for none, or bits of no foot.
  const auto with_database = [](auto change) {
    GraphFile file = sample();
    change(file.database);
    return serialize_graph_file(file);
  };
  expect_error(with_database([](MotionDatabase& db) { db.frame_contacts.pop_back(); }), "inconsistent");
  expect_error(with_database([](MotionDatabase& db) { db.contacts_error = "no feet"; }), "inconsistent");
  expect_error(with_database([](MotionDatabase& db) { db.frame_contacts[3] = 0x10; }), "inconsistent");
  // No contacts with the reason: read as written.
  auto without = parse_graph_file(with_database([](MotionDatabase& db) {
                                    db.frame_contacts.clear();
                                    db.contacts_error = "skeleton '16.asf': no left ankle";
                                  }),
                                  "nofeet.mgraph");
  ASSERT_TRUE(without) << without.error().to_string();
  EXPECT_TRUE(without->database.frame_contacts.empty());
  EXPECT_EQ(without->database.contacts_error, "skeleton '16.asf': no left ankle");
  // A valid cache file is not a graph file.
  expect_error(serialize_distance_cache(1, sample().candidates), "not a motiongraph graph");
}

// Values a checksum cannot vouch for (a file written by another build, or edited and summed
// again) are checked: out of range they would be read outside the motion (a transition leaving
// frame 1e9 crashed walk).
TEST(GraphFile, ValuesOutOfRangeAreRefused) {
  const auto refused = [](const std::function<void(GraphFile&)>& change) {
    GraphFile file = sample();
    change(file);
    auto read = parse_graph_file(serialize_graph_file(file), "bad.mgraph");
    return !read && read.error().message.find("inconsistent") != std::string::npos;
  };
  ASSERT_FALSE(refused([](GraphFile&) {}));
  const int frames = sample().database.frame_count();
  EXPECT_TRUE(refused([](GraphFile& f) { f.graph.transitions[0].from_frame = 1'000'000'000; }));
  EXPECT_TRUE(refused([](GraphFile& f) { f.graph.transitions[0].from_frame = -1; }));
  EXPECT_TRUE(refused([&](GraphFile& f) { f.graph.transitions[0].from_frame = frames - f.graph.window + 1; }));
  EXPECT_FALSE(refused([&](GraphFile& f) { f.graph.transitions[0].from_frame = frames - f.graph.window; }));
  EXPECT_TRUE(refused([&](GraphFile& f) { f.graph.transitions[1].to_frame = frames; }));
  EXPECT_TRUE(refused([&](GraphFile& f) { f.graph.transitions[1].to_frame = f.graph.window - 2; }));
  EXPECT_FALSE(refused([&](GraphFile& f) { f.graph.transitions[1].to_frame = f.graph.window - 1; }));
  EXPECT_TRUE(refused([](GraphFile& f) { f.graph.transitions[0].yaw_rad = std::nanf(""); }));
  EXPECT_TRUE(refused([](GraphFile& f) { f.graph.transitions[1].x_m = INFINITY; }));
  EXPECT_TRUE(refused([](GraphFile& f) { f.candidates.minima[1].to_frame = 1'000'000'000; }));
  EXPECT_TRUE(refused([](GraphFile& f) { f.graph.window = 0; }));
  EXPECT_TRUE(refused([](GraphFile& f) { f.graph.edges[0].frame_count = 100'000'000; }));
  EXPECT_TRUE(refused([](GraphFile& f) { f.graph.nodes[1].clip = 0; }));  // frame 50 is in clip 1
  EXPECT_TRUE(refused([](GraphFile& f) { f.database.fps = INFINITY; }));
  EXPECT_TRUE(refused([](GraphFile& f) { f.database.clips[1].read_fps = -30.0; }));
  EXPECT_TRUE(refused([](GraphFile& f) { f.database.clips[1].read_fps = std::nan(""); }));
  EXPECT_FALSE(refused([](GraphFile& f) { f.database.clips[1].read_fps = 0.0; }));  // not known
  // A clip edge plays its node's frames onward, within the motion.
  EXPECT_FALSE(refused([&](GraphFile& f) {
    f.graph.edges[0] = {0, 1, false, -1, frames - f.graph.nodes[0].frame};
  }));
  EXPECT_TRUE(refused([&](GraphFile& f) {
    f.graph.edges[0] = {0, 1, false, -1, frames - f.graph.nodes[0].frame + 1};
  }));
}

TEST(DistanceCache, RoundTripAndKey) {
  const CandidateSearch candidates = sample().candidates;
  const std::string bytes = serialize_distance_cache(42, candidates);
  auto read = parse_distance_cache(bytes, "c.mgcache", 42);
  ASSERT_TRUE(read) << read.error().to_string();
  EXPECT_EQ(read->minima.size(), candidates.minima.size());
  EXPECT_EQ(read->histogram.counts(), candidates.histogram.counts());
  EXPECT_FALSE(parse_distance_cache(bytes, "c.mgcache", 43));
  EXPECT_NE(content_key("walk"), content_key("walk "));
  EXPECT_EQ(content_key("walk"), content_key(std::string("walk")));
}

// Large payloads are checksummed in one piece per core and the pieces' CRCs combined: the
// same CRC-32 as zlib's over the whole (content_key's upper half), at sizes that split
// unevenly.
TEST(GraphFile, TheChecksumOfALargePayloadIsZlibsOverTheWhole) {
  for (const size_t size : {size_t{70} << 20, (size_t{100} << 20) + 12345}) {
    std::string bytes(size, '\0');
    std::uint32_t state = 12345;
    for (char& c : bytes) {
      state = state * 1664525u + 1013904223u;
      c = static_cast<char>(state >> 24);
    }
    uLong whole = crc32(0L, Z_NULL, 0);
    whole = crc32(whole, reinterpret_cast<const Bytef*>(bytes.data()), static_cast<uInt>(bytes.size()));
    EXPECT_EQ(content_key(bytes) >> 32, static_cast<std::uint64_t>(whole)) << size;
  }
}

}  // namespace
}  // namespace mg
