#include "motiongraph/synthesis/synthesis_context.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "motiongraph/core/text.h"
#include "motiongraph/database/cmu_tags.h"
#include "motiongraph/database/database_contacts.h"
#include "motiongraph/synthesis/travel_heading.h"

namespace mg {

Result<SynthesisContext> make_synthesis_context(const MotionDatabase& db, const MotionGraph& graph,
                                                int target_skeleton) {
  if (graph.node_count() == 0 || db.clips.empty()) return Error{"", 0, "the graph is empty"};
  if (target_skeleton < 0) target_skeleton = db.clips.front().skeleton;
  auto assembler = MotionAssembler::create(db, graph, target_skeleton);
  if (!assembler) return assembler.error();
  SynthesisContext context{&db, &graph, std::move(*assembler), db.frame_tags(), {}, {}, {}, {},
                           std::make_shared<TagCostCache>()};
  // The travel axes once (the hips' axis falls back on the target's), the hips' of the target only.
  const Vec3 travel_axis = learn_travel_axes(db)[target_skeleton];
  const Vec3 forward_axis = learn_forward_axis(db, target_skeleton, travel_axis);
  // The headings as the heading edit holding the travel judges them (steering's search, with
  // either hold, reads them or the facings).
  HeadingEditSettings travel_hold;
  travel_hold.hold_travel = true;
  context.tracks = compute_edge_tracks(context.assembler, graph, context.frame_tags, forward_axis, travel_axis,
                                       travel_turns(db, context.assembler, forward_axis, travel_hold));
  auto feet = find_foot_joints(db.skeletons[target_skeleton], db.foot_names);
  auto contacts = feet ? contacts_of(db) : Result<std::vector<ContactMask>>(feet.error());
  if (feet && contacts) {
    context.feet = *feet;
    context.frame_contacts = std::move(*contacts);
  } else {
    context.feet_error = contacts.error().message;
  }
  return context;
}

namespace {

// The placement moving a root at `root` facing `facing` (floor) to `at` facing `direction`.
FloorTransform place_root(const Vec2& root, Vec2 facing, const Vec2& at, const Vec2& direction) {
  if (facing.isZero()) facing = Vec2(0.0, -1.0);
  // FloorTransform turns the angle atan2(z, x) of a vector by -yaw.
  const double yaw = std::atan2(facing.y(), facing.x()) - std::atan2(direction.y(), direction.x());
  FloorTransform w{yaw, 0.0, 0.0};
  const Vec3 turned = w.apply(Vec3(root.x(), 0.0, root.y()));
  w.x_m = at.x() - turned.x();
  w.z_m = at.y() - turned.z();
  return w;
}

}  // namespace

FloorTransform SynthesisContext::placement_facing(int node, const Vec2& at, const Vec2& direction) const {
  const int frame = graph->nodes[node].frame;
  const Vec3 root = assembler.root_position(frame, {});
  return place_root(Vec2(root.x(), root.z()), facing_on_floor(assembler.root_rotation(frame, {}), tracks.forward_axis),
                    at, direction);
}

FloorTransform SynthesisContext::placement_heading(int node, const Vec2& at, const Vec2& direction) const {
  const int frame = graph->nodes[node].frame;
  const Vec3 root = assembler.root_position(frame, {});
  return place_root(Vec2(root.x(), root.z()), facing_on_floor(assembler.root_rotation(frame, {}), tracks.travel_axis),
                    at, direction);
}

FloorTransform SynthesisContext::placement_heading_edge(int edge, const Vec2& at, const Vec2& direction) const {
  return place_root(tracks.roots_of(edge).front(), tracks.edges[static_cast<size_t>(edge)].first_heading, at, direction);
}

std::vector<ContactMask> SynthesisContext::edges_contacts(std::span<const int> edges) const {
  std::vector<ContactMask> out;
  if (frame_contacts.empty()) return out;
  for (int e : edges) assembler.append_edge_contacts(e, frame_contacts, out);
  return out;
}

const RestEndings& SynthesisContext::rest() const {
  std::call_once(rest_cache->found,
                 [&] { rest_cache->endings = find_rest_endings(*db, *graph, assembler, frame_contacts); });
  return rest_cache->endings;
}

void SynthesisContext::set_rest(RestEndings endings) {
  rest_cache = std::make_shared<RestCache>();
  std::call_once(rest_cache->found, [&] { rest_cache->endings = std::move(endings); });
}

const std::vector<RestStart>& SynthesisContext::rest_starts(int held_frame) const {
  std::lock_guard<std::mutex> lock(start_cache->mutex);
  auto found = start_cache->starts.find(held_frame);
  if (found == start_cache->starts.end()) {
    found = start_cache->starts.emplace(held_frame, find_rest_starts(*db, *graph, assembler, held_frame)).first;
  }
  return found->second;
}

std::vector<ContactMask> SynthesisContext::frames_contacts(std::span<const int> frames) const {
  std::vector<ContactMask> out;
  if (frame_contacts.empty()) return out;
  for (int f : frames) out.push_back(frame_contacts[static_cast<size_t>(f)]);
  return out;
}

std::vector<ContactMask> SynthesisContext::sources_contacts(std::span<const FrameSource> sources) const {
  std::vector<ContactMask> out;
  if (frame_contacts.empty()) return out;
  for (const FrameSource& source : sources) out.push_back(frame_contacts[static_cast<size_t>(source.dominant())]);
  return out;
}

std::vector<ContactMask> SynthesisContext::walk_contacts(const Walk& walk) const {
  return frame_contacts.empty() ? std::vector<ContactMask>{} : sources_contacts(walk_sources(walk));
}

std::vector<FrameSource> SynthesisContext::walk_sources(const Walk& walk) const {
  std::vector<FrameSource> out;
  for (int e : walk.edges) assembler.append_edge_sources(e, out);
  for (int f : walk.rest_frames) out.push_back({f, f, 1.0});
  if (walk.rest_frames.empty() && walk.start_node >= 0) {
    const int end = graph->nodes[walk.end_node(*graph)].frame;
    out.push_back({end, end, 1.0});
  }
  return out;
}

std::vector<TagMask> SynthesisContext::walk_tags(const Walk& walk) const {
  std::vector<TagMask> out;
  for (int e : walk.edges) {
    const auto tags = tracks.tags_of(e);
    out.insert(out.end(), tags.begin(), tags.end());
  }
  for (int f : walk.rest_frames) out.push_back(frame_tag(f));
  if (walk.rest_frames.empty() && walk.start_node >= 0) {
    out.push_back(frame_tag(graph->nodes[walk.end_node(*graph)].frame));
  }
  return out;
}

Result<FootCleanup> SynthesisContext::foot_cleanup(const FootCleanupSettings& settings) const {
  if (frame_contacts.empty()) return Error{"", 0, "no foot clean-up: " + feet_error};
  return FootCleanup::create(assembler.skeleton(), feet, db->fps, settings);
}

Status SynthesisContext::clean_up_walk(const Walk& walk, FootCleanup& cleanup, Motion& motion) const {
  std::vector<ContactMask> contacts = walk_contacts(walk);
  if (static_cast<int>(contacts.size()) < motion.frame_count) {
    return Error{"", 0, fmt::format("the walk plays {} frames, the motion has {}", contacts.size(), motion.frame_count)};
  }
  contacts.resize(static_cast<size_t>(motion.frame_count));
  return cleanup.clean(motion, 0, contacts);
}

Result<TagMask> SynthesisContext::tag_mask(const std::string& name) const {
  const std::string lower = ascii_lower(name);
  std::vector<size_t> any_case;  // the tags of that name in another case
  for (size_t t = 0; t < db->tag_names.size(); ++t) {
    if (db->tag_names[t] == name) return TagMask{1} << t;
    if (ascii_lower(db->tag_names[t]) == lower) any_case.push_back(t);
  }
  if (any_case.size() == 1) return TagMask{1} << any_case.front();
  std::string means;
  if (any_case.size() > 1) {
    means = fmt::format("; in another case it names {} of them: give it as written", any_case.size());
  } else {
    // A word the clips' names and descriptions read as a tag the graph has ("sprint": run).
    const std::vector<std::string> read_as = clip_name_tags(name);
    const auto has = [&](const std::string& tag) {
      return std::any_of(db->tag_names.begin(), db->tag_names.end(),
                         [&](const std::string& t) { return ascii_lower(t) == tag; });
    };
    if (read_as.size() == 1 && read_as.front() != lower && has(read_as.front())) {
      means = fmt::format("; {} is a word for '{}'", quoted(name), read_as.front());
    }
  }
  // (quoted: at most 40 characters of it, control bytes escaped; a request could hold 100 KB)
  return Error{"", 0, fmt::format("{} is not a motion tag of this graph (its tags: {}){}", quoted(name),
                                  db->tag_names.empty() ? "none" : fmt::format("{}", fmt::join(db->tag_names, ", ")),
                                  means)};
}

Result<std::string> SynthesisContext::tag_name(const std::string& name) const {
  auto mask = tag_mask(name);
  if (!mask) return mask.error();
  return db->tag_names_of(*mask).front();
}

}  // namespace mg
