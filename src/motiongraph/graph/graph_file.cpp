#include "motiongraph/graph/graph_file.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <initializer_list>
#include <limits>
#include <vector>

#include <zlib.h>

#include <fmt/format.h>

#include "motiongraph/core/binary.h"
#include "motiongraph/core/parallel_for.h"
#include "motiongraph/io/file.h"

namespace mg {

namespace {

constexpr std::string_view kGraphMagic("MGRAPH\r\n\x1a", 9);
constexpr std::string_view kCacheMagic("MGCACHE\r\n\x1a", 10);
constexpr std::uint32_t kCacheVersion = 2;
constexpr std::string_view kPartMagic("MGTILES\r\n\x1a", 10);
constexpr std::uint32_t kPartVersion = 1;

std::uint32_t crc32_serial(std::string_view bytes) {
  uLong crc = crc32(0L, Z_NULL, 0);
  // zlib takes 32-bit lengths: feed large payloads in pieces.
  while (!bytes.empty()) {
    const size_t piece = std::min<size_t>(bytes.size(), 1u << 30);
    crc = crc32(crc, reinterpret_cast<const Bytef*>(bytes.data()), static_cast<uInt>(piece));
    bytes.remove_prefix(piece);
  }
  return static_cast<std::uint32_t>(crc);
}

// The CRC-32 of `bytes`: of large payloads (a whole library's graph is hundreds of MB) in one
// piece per core, joined with zlib's crc32_combine, which gives the same value.
std::uint32_t crc32_of(std::string_view bytes) {
  constexpr size_t kPieceFloor = 32u << 20;
  const size_t pieces = std::min<size_t>(static_cast<size_t>(worker_threads(0)),
                                         std::max<size_t>(1, bytes.size() / kPieceFloor));
  if (pieces == 1) return crc32_serial(bytes);
  auto begin_of = [&](size_t piece) { return bytes.size() * piece / pieces; };
  std::vector<std::uint32_t> crcs(pieces);
  parallel_for(static_cast<long long>(pieces), static_cast<int>(pieces), 1, [&](int, long long p) {
    const auto piece = static_cast<size_t>(p);
    crcs[piece] = crc32_serial(bytes.substr(begin_of(piece), begin_of(piece + 1) - begin_of(piece)));
  });
  uLong crc = crcs[0];
  for (size_t p = 1; p < pieces; ++p) {
    crc = crc32_combine(crc, crcs[p], static_cast<z_off_t>(begin_of(p + 1) - begin_of(p)));
  }
  return static_cast<std::uint32_t>(crc);
}

// Files are framed as: the magic, the format version (u32), then for each of the file type's
// sections its size (u64) and CRC-32 (u32), then the sections' bytes in order. A file of one
// section (cache, part) is thus magic, version, size, CRC, payload.
std::string frame(std::string_view magic, std::uint32_t version, std::initializer_list<std::string_view> sections) {
  BinaryWriter out;
  out.put(version);
  for (std::string_view section : sections) {
    out.put<std::uint64_t>(section.size());
    out.put(crc32_of(section));
  }
  std::string bytes(magic);
  bytes += out.data();
  for (std::string_view section : sections) bytes += section;
  return bytes;
}

// The file's `count` sections, each checked against its CRC-32 when its bit is set in `check`
// (a reader that will not read a section does not pay for its checksum).
Result<std::vector<std::string_view>> unframe(std::string_view bytes, const std::string& file_name,
                                              std::string_view magic, std::uint32_t version, const char* what,
                                              size_t count, unsigned check) {
  if (bytes.size() < magic.size() || bytes.substr(0, magic.size()) != magic) {
    return Error{file_name, 0, fmt::format("not a motiongraph {} file", what)};
  }
  BinaryReader in(bytes.substr(magic.size()), file_name);
  std::uint32_t file_version = 0;
  if (!in.get(file_version)) return Error{file_name, 0, "truncated header"};
  if (file_version < version) {
    return Error{file_name, 0,
                 fmt::format("{} file format version {}, an older motiongraph's; this one reads version {}: build it "
                             "again",
                             what, file_version, version)};
  }
  if (file_version > version) {
    return Error{file_name, 0,
                 fmt::format("{} file format version {}, a newer motiongraph's; this one reads version {}: open it "
                             "with the motiongraph that wrote it, or build it again with this one",
                             what, file_version, version)};
  }
  std::vector<std::uint64_t> sizes(count);
  std::vector<std::uint32_t> crcs(count);
  for (size_t i = 0; i < count; ++i) {
    if (!in.get(sizes[i]) || !in.get(crcs[i])) return Error{file_name, 0, "truncated header"};
  }
  std::string_view rest = bytes.substr(magic.size() + in.position());
  std::uint64_t total = 0;
  for (std::uint64_t size : sizes) total = size > UINT64_MAX - total ? UINT64_MAX : total + size;
  if (rest.size() != total) {
    const char* wrong = rest.size() < total ? "truncated" : "longer than its header says (bytes added at its end?)";
    return Error{file_name, 0, fmt::format("{}: {} bytes of payload, the header says {}", wrong, rest.size(), total)};
  }
  std::vector<std::string_view> sections;
  for (size_t i = 0; i < count; ++i) {
    sections.push_back(rest.substr(0, sizes[i]));
    rest.remove_prefix(sizes[i]);
    if ((check >> i & 1u) != 0 && crc32_of(sections.back()) != crcs[i]) {
      return Error{file_name, 0, "checksum mismatch: the file is damaged"};
    }
  }
  return sections;
}

// One section, checked.
Result<std::string_view> unframe(std::string_view bytes, const std::string& file_name, std::string_view magic,
                                 std::uint32_t version, const char* what) {
  auto sections = unframe(bytes, file_name, magic, version, what, 1, 1u);
  if (!sections) return sections.error();
  return sections->front();
}

// --- pieces ---------------------------------------------------------------------------------

void put_skeleton(BinaryWriter& out, const Skeleton& skeleton) {
  out.put<std::int32_t>(skeleton.joint_count());
  for (const JointDef& joint : skeleton.joints()) {
    out.put_string(joint.name);
    out.put<std::int32_t>(joint.parent);
    for (int i = 0; i < 3; ++i) out.put(joint.rest_offset_m[i]);
    out.put<std::uint8_t>(joint.end_site);
    out.put<std::uint8_t>(joint.animated_translation);
    for (Axis axis : joint.euler_order) out.put<std::uint8_t>(static_cast<std::uint8_t>(axis));
  }
  out.put<std::int32_t>(static_cast<std::int32_t>(skeleton.static_ancestors().size()));
  for (const StaticAncestor& a : skeleton.static_ancestors()) {
    out.put_string(a.name);
    for (int i = 0; i < 3; ++i) out.put(a.translation_m[i]);
    for (double c : {a.rotation.w(), a.rotation.x(), a.rotation.y(), a.rotation.z()}) out.put(c);
    out.put<std::uint8_t>(a.position_channels);
    for (Axis axis : a.euler_order) out.put<std::uint8_t>(static_cast<std::uint8_t>(axis));
  }
}

bool get_euler_order(BinaryReader& in, ComposeOrder& order) {
  for (Axis& axis : order) {
    std::uint8_t value = 0;
    if (!in.get(value) || value > 2) return false;
    axis = static_cast<Axis>(value);
  }
  return true;
}

bool get_static_ancestors(BinaryReader& in, std::vector<StaticAncestor>& ancestors) {
  std::int32_t count = 0;
  if (!in.get(count) || count < 0 || count > 1000) return false;
  ancestors.resize(static_cast<size_t>(count));
  for (StaticAncestor& a : ancestors) {
    double w = 0, x = 0, y = 0, z = 0;
    std::uint8_t positions = 0;
    if (!in.get_string(a.name)) return false;
    for (int i = 0; i < 3; ++i) {
      if (!in.get(a.translation_m[i])) return false;
    }
    if (!in.get(w) || !in.get(x) || !in.get(y) || !in.get(z) || !in.get(positions)) return false;
    a.rotation = Quat(w, x, y, z);
    a.position_channels = positions != 0;
    if (!get_euler_order(in, a.euler_order)) return false;
  }
  return true;
}

bool get_skeleton(BinaryReader& in, Skeleton& skeleton) {
  std::int32_t count = 0;
  if (!in.get(count) || count < 1 || count > 100000) return false;
  std::vector<JointDef> joints(count);
  for (int j = 0; j < count; ++j) {
    JointDef& joint = joints[j];
    std::uint8_t end = 0, translated = 0;
    if (!in.get_string(joint.name) || !in.get(joint.parent)) return false;
    for (int i = 0; i < 3; ++i) {
      if (!in.get(joint.rest_offset_m[i])) return false;
    }
    if (!in.get(end) || !in.get(translated) || !get_euler_order(in, joint.euler_order)) return false;
    if ((j == 0) != (joint.parent < 0) || joint.parent >= j) return false;
    joint.end_site = end != 0;
    joint.animated_translation = translated != 0;
  }
  std::vector<StaticAncestor> ancestors;
  if (!get_static_ancestors(in, ancestors)) return false;
  skeleton = Skeleton(std::move(joints), std::move(ancestors));
  return true;
}

void put_motion(BinaryWriter& out, const Motion& motion) {
  out.put(motion.fps);
  out.put<std::int32_t>(motion.frame_count);
  std::vector<float> rotations(motion.local_rotations.size() * 4);
  for (size_t i = 0; i < motion.local_rotations.size(); ++i) {
    const Quat& q = motion.local_rotations[i];
    rotations[4 * i] = static_cast<float>(q.w());
    rotations[4 * i + 1] = static_cast<float>(q.x());
    rotations[4 * i + 2] = static_cast<float>(q.y());
    rotations[4 * i + 3] = static_cast<float>(q.z());
  }
  out.put_vector(rotations);
  std::vector<double> translations(motion.local_translations_m.size() * 3);
  for (size_t i = 0; i < motion.local_translations_m.size(); ++i) {
    for (int c = 0; c < 3; ++c) translations[3 * i + c] = motion.local_translations_m[i][c];
  }
  out.put_vector(translations);
}

// The highest frame rate a file may hold (a rate past any capture's; finite).
constexpr double kMaxStoredFps = 1e6;

// A clip's motion as stored: checked against its skeleton, decoded later (decode_motion).
struct StoredMotion {
  double fps = 0.0;
  std::int32_t frames = 0;
  const char* rotations = nullptr;     // frames x joints x 4 floats (w, x, y, z)
  const char* translations = nullptr;  // frames x translated joints x 3 doubles
};

bool get_stored_motion(BinaryReader& in, const Skeleton& skeleton, StoredMotion& stored) {
  std::uint64_t rotation_values = 0, translation_values = 0;
  if (!in.get(stored.fps) || !in.get(stored.frames) || !(stored.fps > 0.0 && stored.fps <= kMaxStoredFps) ||
      stored.frames < 0) {
    return false;
  }
  if (!in.view_vector<float>(rotation_values, stored.rotations) ||
      !in.view_vector<double>(translation_values, stored.translations)) {
    return false;
  }
  const auto frames = static_cast<std::uint64_t>(stored.frames);
  return rotation_values == frames * static_cast<std::uint64_t>(skeleton.joint_count()) * 4 &&
         translation_values == frames * skeleton.translated_joints().size() * 3;
}

// The values of a motion made with room for them (Motion's memory constructor), decoded in
// place from the file's bytes (a large library's motion is most of what synthesis reads).
void decode_motion(const StoredMotion& stored, Motion& motion) {
  for (size_t i = 0; i < motion.local_rotations.size(); ++i) {
    float q[4];
    std::memcpy(q, stored.rotations + 4 * i * sizeof(float), sizeof(q));
    // Kept as stored (unit to float precision), so that writing what was read is exact.
    motion.local_rotations[i] = Quat(q[0], q[1], q[2], q[3]);
  }
  for (size_t i = 0; i < motion.local_translations_m.size(); ++i) {
    double v[3];
    std::memcpy(v, stored.translations + 3 * i * sizeof(double), sizeof(v));
    motion.local_translations_m[i] = Vec3(v[0], v[1], v[2]);
  }
}

void put_database(BinaryWriter& out, const MotionDatabase& db) {
  out.put(db.fps);
  out.put<std::int32_t>(static_cast<std::int32_t>(db.skeletons.size()));
  for (size_t s = 0; s < db.skeletons.size(); ++s) {
    out.put_string(s < db.skeleton_names.size() ? db.skeleton_names[s] : "");
    put_skeleton(out, db.skeletons[s]);
  }
  out.put<std::int32_t>(static_cast<std::int32_t>(db.clips.size()));
  for (const DatabaseClip& clip : db.clips) {
    out.put_string(clip.name);
    out.put_string(clip.source);
    out.put<std::int32_t>(clip.skeleton);
    out.put<std::int32_t>(clip.first_frame);
    out.put<std::int32_t>(clip.frame_count);
    out.put(clip.read_fps);
    put_motion(out, clip.motion);
  }
  out.put<std::int32_t>(static_cast<std::int32_t>(db.tag_names.size()));
  for (const std::string& name : db.tag_names) out.put_string(name);
  out.put<std::int32_t>(static_cast<std::int32_t>(db.tag_ranges.size()));
  for (const TagRange& range : db.tag_ranges) {
    out.put<std::int32_t>(range.tag);
    out.put<std::int32_t>(range.first_frame);
    out.put<std::int32_t>(range.frame_count);
  }
  for (const std::string* name : {&db.foot_names.left_ankle, &db.foot_names.left_toe, &db.foot_names.right_ankle,
                                  &db.foot_names.right_toe}) {
    out.put_string(*name);
  }
  out.put_vector(db.frame_contacts);
  out.put_string(db.contacts_error);
}

bool get_database(BinaryReader& in, MotionDatabase& db) {
  std::int32_t skeletons = 0, clips = 0, tags = 0, ranges = 0;
  if (!in.get(db.fps) || !(db.fps > 0.0 && db.fps <= kMaxStoredFps) || !in.get(skeletons) || skeletons < 0 ||
      skeletons > 100000) {
    return false;
  }
  db.skeletons.resize(skeletons);
  db.skeleton_names.resize(skeletons);
  for (int s = 0; s < skeletons; ++s) {
    if (!in.get_string(db.skeleton_names[s]) || !get_skeleton(in, db.skeletons[s])) return false;
  }
  if (!in.get(clips) || clips < 0 || clips > 10000000) return false;
  int next_frame = 0;
  std::vector<DatabaseClip> headers;  // all but the motion
  std::vector<StoredMotion> stored;
  size_t motion_bytes = 0;
  for (int c = 0; c < clips; ++c) {
    DatabaseClip clip;
    if (!in.get_string(clip.name) || !in.get_string(clip.source) || !in.get(clip.skeleton) ||
        !in.get(clip.first_frame) || !in.get(clip.frame_count) || !in.get(clip.read_fps)) {
      return false;
    }
    if (clip.skeleton < 0 || clip.skeleton >= skeletons || clip.first_frame != next_frame || clip.frame_count < 1 ||
        !(clip.read_fps >= 0.0 && clip.read_fps <= kMaxStoredFps)) {
      return false;
    }
    const Skeleton& skeleton = db.skeletons[clip.skeleton];
    StoredMotion motion;
    if (!get_stored_motion(in, skeleton, motion) || motion.frames != clip.frame_count) return false;
    next_frame += clip.frame_count;
    const auto frames = static_cast<size_t>(clip.frame_count);
    // Each vector's bytes and room to align it.
    motion_bytes += frames * static_cast<size_t>(skeleton.joint_count()) * sizeof(Quat) + alignof(Quat) +
                    frames * skeleton.translated_joints().size() * sizeof(Vec3) + alignof(Vec3);
    headers.push_back(std::move(clip));
    stored.push_back(motion);
  }
  // All the clips' motion in one block (core/huge_pages.h), made here, then decoded on all cores.
  db.motion_memory = std::make_shared<HugePageArena>(motion_bytes);
  db.clips.reserve(headers.size());
  for (size_t c = 0; c < headers.size(); ++c) {
    DatabaseClip& h = headers[c];
    const Skeleton& skeleton = db.skeletons[h.skeleton];
    db.clips.push_back(DatabaseClip{std::move(h.name), std::move(h.source), h.skeleton, h.first_frame, h.frame_count,
                                    Motion(skeleton, h.frame_count, stored[c].fps, db.motion_memory->resource()),
                                    h.read_fps});
  }
  parallel_for(clips, worker_threads(0), 1, [&](int, long long c) {
    decode_motion(stored[static_cast<size_t>(c)], db.clips[static_cast<size_t>(c)].motion);
  });
  if (!in.get(tags) || tags < 0 || tags > 64) return false;
  db.tag_names.resize(tags);
  for (auto& name : db.tag_names) {
    if (!in.get_string(name)) return false;
  }
  if (!in.get(ranges) || ranges < 0) return false;
  for (int r = 0; r < ranges; ++r) {
    TagRange range;
    if (!in.get(range.tag) || !in.get(range.first_frame) || !in.get(range.frame_count)) return false;
    if (range.tag < 0 || range.tag >= tags || range.first_frame < 0 || range.frame_count < 0 ||
        range.first_frame + static_cast<long long>(range.frame_count) > next_frame) {
      return false;
    }
    db.tag_ranges.push_back(range);
  }
  for (std::string* name : {&db.foot_names.left_ankle, &db.foot_names.left_toe, &db.foot_names.right_ankle,
                            &db.foot_names.right_toe}) {
    if (!in.get_string(*name)) return false;
  }
  if (!in.get_vector(db.frame_contacts) || !in.get_string(db.contacts_error)) return false;
  // Contacts for every frame, or none with the reason.
  if (!db.frame_contacts.empty() && static_cast<int>(db.frame_contacts.size()) != next_frame) return false;
  if (!db.frame_contacts.empty() && !db.contacts_error.empty()) return false;
  const ContactMask all = contact_bit(FootSide::kLeft, FootPart::kAnkle) | contact_bit(FootSide::kLeft, FootPart::kToe) |
                          contact_bit(FootSide::kRight, FootPart::kAnkle) | contact_bit(FootSide::kRight, FootPart::kToe);
  for (const ContactMask m : db.frame_contacts) {
    if ((m & ~all) != 0) return false;
  }
  return true;
}

// The candidate search, with its minima or (a graph file, which keeps them in a section of
// their own) without.
void put_candidates(BinaryWriter& out, const CandidateSearch& c, bool with_minima = true) {
  out.put<std::int32_t>(c.window);
  out.put<std::int32_t>(c.continuation_radius);
  if (with_minima) out.put_vector(c.minima);
  out.put_vector(c.histogram.counts());
  out.put_vector(c.picture);
  out.put<std::int32_t>(c.picture_side);
  out.put<std::int32_t>(c.picture_block);
  out.put(c.tiles.seconds);
  out.put(c.tiles.tiles);
  out.put(c.tiles.pairs);
  out.put(c.ceiling);
  out.put<std::int32_t>(c.tile_frames);
}

bool get_candidates(BinaryReader& in, CandidateSearch& c, bool with_minima = true) {
  std::vector<std::uint64_t> counts;
  if (!in.get(c.window) || !in.get(c.continuation_radius) || (with_minima && !in.get_vector(c.minima)) ||
      !in.get_vector(counts) ||
      !in.get_vector(c.picture) || !in.get(c.picture_side) || !in.get(c.picture_block) || !in.get(c.tiles.seconds) ||
      !in.get(c.tiles.tiles) || !in.get(c.tiles.pairs) || !in.get(c.ceiling) || !in.get(c.tile_frames)) {
    return false;
  }
  if (counts.size() != static_cast<size_t>(DistanceHistogram::kBins) || c.window < 1 || c.picture_side < 0 ||
      c.picture.size() != static_cast<size_t>(c.picture_side) * c.picture_side) {
    return false;
  }
  c.histogram.set_counts(std::move(counts));
  return true;
}

void put_graph(BinaryWriter& out, const MotionGraph& g) {
  out.put<std::int32_t>(g.window);
  out.put_vector(g.nodes);
  // GraphEdge has padding after `transition` and after `bridge`: written as zeros, so that one
  // graph always gives the same bytes (its fields are set one by one on zeroed memory).
  std::vector<GraphEdge> edges(g.edges.size());
  std::memset(static_cast<void*>(edges.data()), 0, edges.size() * sizeof(GraphEdge));
  for (size_t i = 0; i < edges.size(); ++i) {
    edges[i].from_node = g.edges[i].from_node;
    edges[i].to_node = g.edges[i].to_node;
    edges[i].transition = g.edges[i].transition;
    edges[i].bridge = g.edges[i].bridge;
    edges[i].transition_index = g.edges[i].transition_index;
    edges[i].frame_count = g.edges[i].frame_count;
    edges[i].blend_lead = g.edges[i].blend_lead;
  }
  out.put_vector(edges);
  out.put_vector(g.edge_offsets);
  out.put_vector(g.transitions);
}

// Whether the byte of a bool member read from a file is 0 or 1 (any other is no bool: reading it
// as one is undefined). The object's bytes may be inspected as unsigned char.
bool bool_byte_valid(const GraphEdge& edge, size_t offset) {
  return reinterpret_cast<const unsigned char*>(&edge)[offset] <= 1;
}

// A transition's windows lie within the database's frames (it leaves from_frame's window and
// arrives at to_frame's), and its floor alignment is finite. A file whose checksum holds may still
// carry other values (written by another build, or edited): out of range, they would be read
// outside the motion.
bool transition_in_range(const Transition& t, int frames, int window) {
  return t.from_frame >= 0 && t.from_frame <= frames - window && t.to_frame >= window - 1 && t.to_frame < frames &&
         std::isfinite(t.yaw_rad) && std::isfinite(t.x_m) && std::isfinite(t.z_m);
}

bool get_graph(BinaryReader& in, const MotionDatabase& db, MotionGraph& g) {
  if (!in.get(g.window) || !in.get_vector(g.nodes) || !in.get_vector(g.edges) || !in.get_vector(g.edge_offsets) ||
      !in.get_vector(g.transitions)) {
    return false;
  }
  for (const GraphEdge& e : g.edges) {
    if (!bool_byte_valid(e, offsetof(GraphEdge, transition)) || !bool_byte_valid(e, offsetof(GraphEdge, bridge))) {
      return false;
    }
  }
  const int nodes = g.node_count();
  const int frames = db.frame_count();
  if (g.window < 1 || g.window > frames) return false;
  for (const Transition& t : g.transitions) {
    if (!transition_in_range(t, frames, g.window)) return false;
  }
  if (g.edge_offsets.size() != static_cast<size_t>(nodes) + 1 || g.edge_offsets.front() != 0 ||
      g.edge_offsets.back() != g.edge_count()) {
    return false;
  }
  for (int n = 0; n < nodes; ++n) {
    if (g.edge_offsets[n] > g.edge_offsets[n + 1]) return false;
    if (g.nodes[n].frame < 0 || g.nodes[n].frame >= frames || g.nodes[n].clip != db.clip_of(g.nodes[n].frame)) {
      return false;
    }
  }
  for (const GraphEdge& e : g.edges) {
    if (e.from_node < 0 || e.from_node >= nodes || e.to_node < 0 || e.to_node >= nodes || e.frame_count < 0 ||
        e.frame_count > frames) {
      return false;
    }
    if (e.bridge && !e.transition) return false;
    if (!e.transition && g.nodes[e.from_node].frame + e.frame_count > frames) return false;
    // A lead only on a bridge, and within the frames its blend has beyond the window.
    if (e.blend_lead < 0 || (e.blend_lead > 0 && (!e.bridge || e.blend_lead > e.frame_count + 1 - g.window))) {
      return false;
    }
    if (e.transition && (e.transition_index < 0 || e.transition_index >= static_cast<int>(g.transitions.size()))) {
      return false;
    }
  }
  return true;
}

}  // namespace

std::uint64_t content_key(std::string_view bytes) {
  uLong adler = adler32(0L, Z_NULL, 0);
  std::string_view rest = bytes;
  while (!rest.empty()) {
    const size_t piece = std::min<size_t>(rest.size(), 1u << 30);
    adler = adler32(adler, reinterpret_cast<const Bytef*>(rest.data()), static_cast<uInt>(piece));
    rest.remove_prefix(piece);
  }
  return (static_cast<std::uint64_t>(crc32_of(bytes)) << 32) | static_cast<std::uint32_t>(adler);
}

std::string serialize_graph_file(const GraphFile& file) {
  BinaryWriter out;
  out.put_string(file.settings_json);
  out.put(file.input_key);
  put_database(out, file.database);
  put_candidates(out, file.candidates, false);
  out.put(file.threshold);
  out.put(file.threshold_quantile);
  out.put<std::int32_t>(file.locality_radius);
  put_graph(out, file.graph);
  out.put_string(file.report_json);
  BinaryWriter minima;
  minima.put_vector(file.candidates.minima);
  return frame(kGraphMagic, kGraphFileVersion, {out.data(), minima.data()});
}

Result<GraphFile> parse_graph_file(std::string_view bytes, const std::string& file_name,
                                   const GraphReadOptions& options) {
  auto sections = unframe(bytes, file_name, kGraphMagic, kGraphFileVersion, "graph (.mgraph)", 2,
                          options.candidate_minima ? 3u : 1u);
  if (!sections) return sections.error();
  BinaryReader in((*sections)[0], file_name);
  GraphFile file;
  bool read = in.get_string(file.settings_json) && in.get(file.input_key) && get_database(in, file.database) &&
              get_candidates(in, file.candidates, false) && in.get(file.threshold) &&
              in.get(file.threshold_quantile) && in.get(file.locality_radius) &&
              get_graph(in, file.database, file.graph) && in.get_string(file.report_json) && in.at_end();
  if (read && options.candidate_minima) {
    BinaryReader minima((*sections)[1], file_name);
    read = minima.get_vector(file.candidates.minima) && minima.at_end() &&
           std::all_of(file.candidates.minima.begin(), file.candidates.minima.end(), [&](const Transition& t) {
             return transition_in_range(t, file.database.frame_count(), file.candidates.window);
           });
  }
  if (!read) return Error{file_name, 0, "inconsistent graph file (written by a different build?)"};
  return file;
}

std::string serialize_distance_cache(std::uint64_t key, const CandidateSearch& candidates) {
  BinaryWriter out;
  out.put(key);
  put_candidates(out, candidates);
  return frame(kCacheMagic, kCacheVersion, {out.data()});
}

Result<CandidateSearch> parse_distance_cache(std::string_view bytes, const std::string& file_name,
                                             std::uint64_t expected_key) {
  auto payload = unframe(bytes, file_name, kCacheMagic, kCacheVersion, "distance cache (.mgcache)");
  if (!payload) return payload.error();
  BinaryReader in(*payload, file_name);
  std::uint64_t key = 0;
  CandidateSearch candidates;
  if (!in.get(key)) return Error{file_name, 0, "truncated cache"};
  if (key != expected_key) return Error{file_name, 0, "cache for other inputs or settings"};
  if (!get_candidates(in, candidates) || !in.at_end()) return Error{file_name, 0, "inconsistent cache file"};
  return candidates;
}

std::string serialize_candidate_part(const CandidatePart& part) {
  BinaryWriter out;
  out.put(part.key);
  out.put(part.frames);
  out.put(part.tile_frames);
  out.put_vector(part.items);
  out.put(part.peak_memory_mb);
  const CandidateSearch& c = part.search;
  out.put<std::int32_t>(c.window);
  out.put<std::int32_t>(c.continuation_radius);
  out.put_vector(c.minima);
  out.put_vector(c.histogram.counts());
  out.put<std::int32_t>(c.picture_side);
  out.put<std::int32_t>(c.picture_block);
  std::vector<std::uint32_t> pixel_at;
  std::vector<float> pixel_value;
  for (size_t i = 0; i < c.picture.size(); ++i) {
    if (c.picture[i] == c.picture[i]) {
      pixel_at.push_back(static_cast<std::uint32_t>(i));
      pixel_value.push_back(c.picture[i]);
    }
  }
  out.put_vector(pixel_at);
  out.put_vector(pixel_value);
  out.put(c.tiles.seconds);
  out.put(c.tiles.tiles);
  out.put(c.tiles.pairs);
  return frame(kPartMagic, kPartVersion, {out.data()});
}

Result<CandidatePart> parse_candidate_part(std::string_view bytes, const std::string& file_name) {
  auto payload = unframe(bytes, file_name, kPartMagic, kPartVersion, "distance stage part (.mgtiles)");
  if (!payload) return payload.error();
  BinaryReader in(*payload, file_name);
  CandidatePart part;
  CandidateSearch& c = part.search;
  std::vector<std::uint64_t> counts;
  std::vector<std::uint32_t> pixel_at;
  std::vector<float> pixel_value;
  const bool read = in.get(part.key) && in.get(part.frames) && in.get(part.tile_frames) && in.get_vector(part.items) &&
                    in.get(part.peak_memory_mb) && in.get(c.window) && in.get(c.continuation_radius) &&
                    in.get_vector(c.minima) && in.get_vector(counts) && in.get(c.picture_side) &&
                    in.get(c.picture_block) && in.get_vector(pixel_at) && in.get_vector(pixel_value) &&
                    in.get(c.tiles.seconds) && in.get(c.tiles.tiles) && in.get(c.tiles.pairs) && in.at_end();
  const size_t pixels = static_cast<size_t>(std::max(0, c.picture_side)) * std::max(0, c.picture_side);
  if (!read || counts.size() != static_cast<size_t>(DistanceHistogram::kBins) || c.window < 1 || c.picture_side < 0 ||
      pixel_at.size() != pixel_value.size() ||
      std::any_of(pixel_at.begin(), pixel_at.end(), [&](std::uint32_t i) { return i >= pixels; })) {
    return Error{file_name, 0, "inconsistent distance stage part"};
  }
  c.histogram.set_counts(std::move(counts));
  c.picture.assign(pixels, std::numeric_limits<float>::quiet_NaN());
  for (size_t i = 0; i < pixel_at.size(); ++i) c.picture[pixel_at[i]] = pixel_value[i];
  return part;
}

Result<GraphFile> load_graph_file(const std::string& path, const GraphReadOptions& options) {
  auto bytes = FileBytes::open(path);
  if (!bytes) return bytes.error();
  return parse_graph_file(bytes->bytes(), path, options);
}

}  // namespace mg
