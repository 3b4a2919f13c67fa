#include "motiongraph/synthesis/assembler.h"

#include <fmt/format.h>

#include "motiongraph/database/clip_on_skeleton.h"

namespace mg {

double blend_weight(int p, int k) {
  const double u = static_cast<double>(p + 1) / k;
  return 2.0 * u * u * u - 3.0 * u * u + 1.0;
}

Result<MotionAssembler> MotionAssembler::create(const MotionDatabase& db, const MotionGraph& graph,
                                                int target_skeleton) {
  if (target_skeleton < 0 || target_skeleton >= static_cast<int>(db.skeletons.size())) {
    return Error{"", 0, fmt::format("target skeleton {} does not exist (the database has {})", target_skeleton,
                                    db.skeletons.size())};
  }
  const Skeleton& target = db.skeletons[target_skeleton];
  if (target.joint_count() == 0 || target.translation_slot(0) != 0) {
    return Error{"", 0, "the root joint has no per-frame translation: motion cannot be placed on the floor"};
  }
  MotionAssembler a;
  a.db_ = &db;
  a.graph_ = &graph;
  a.target_ = target_skeleton;
  for (size_t s = 0; s < db.skeletons.size(); ++s) {
    const Skeleton& other = db.skeletons[s];
    if (other.joint_count() != target.joint_count() ||
        other.translated_joints().size() != target.translated_joints().size() || other.translation_slot(0) != 0) {
      return Error{"", 0, fmt::format("skeletons '{}' and '{}' differ in joints or translated joints",
                                      db.skeleton_names[s], db.skeleton_names[target_skeleton])};
    }
    a.scale_.push_back(leg_scale(target, other));
  }
  a.clip_of_frame_.resize(static_cast<size_t>(db.frame_count()));
  for (size_t c = 0; c < db.clips.size(); ++c) {
    for (int f = 0; f < db.clips[c].frame_count; ++f) a.clip_of_frame_[db.clips[c].first_frame + f] = static_cast<int>(c);
  }
  return a;
}

Motion MotionAssembler::empty_motion() const { return Motion(skeleton(), 0, db_->fps); }

const DatabaseClip& MotionAssembler::clip_of(int frame, int* local) const {
  const DatabaseClip& clip = db_->clips[clip_of_frame_[frame]];
  *local = frame - clip.first_frame;
  return clip;
}

RootPose MotionAssembler::root_pose(int frame, const PreparedFloorTransform& placement) const {
  int local = 0;
  const DatabaseClip& clip = clip_of(frame, &local);
  return {placement.apply(scale_[clip.skeleton] * clip.motion.translations(local)[0]),
          placement.rotation * clip.motion.rotations(local)[0]};
}

RootPose MotionAssembler::blend_root(int departure, const PreparedFloorTransform& w_departure, int arrival,
                                     const PreparedFloorTransform& w_arrival, double alpha) const {
  const RootPose d = root_pose(departure, w_departure), a = root_pose(arrival, w_arrival);
  return {alpha * d.position + (1.0 - alpha) * a.position, d.rotation.slerp(1.0 - alpha, a.rotation).normalized()};
}

FloorTransform MotionAssembler::transition_transform(const Transition& t) const {
  int local_a = 0, local_b = 0;
  const double s_a = scale_[clip_of(t.from_frame, &local_a).skeleton];
  const DatabaseClip& arrival = clip_of(t.to_frame, &local_b);
  const double s_b = scale_[arrival.skeleton];
  FloorTransform transform{t.yaw_rad, s_a * t.x_m, s_a * t.z_m};
  if (s_a != s_b) {
    Vec3 c_b = arrival.motion.translations(local_b)[0];
    c_b.y() = 0.0;
    const Vec3 shift = FloorTransform{t.yaw_rad, 0.0, 0.0}.rotate((s_a - s_b) * c_b);
    transform.x_m += shift.x();
    transform.z_m += shift.z();
  }
  return transform;
}

void MotionAssembler::append_frame(int frame, const PreparedFloorTransform& placement, Motion& out) const {
  int local = 0;
  const DatabaseClip& clip = clip_of(frame, &local);
  const double s = scale_[clip.skeleton];
  const auto rotations = clip.motion.rotations(local);
  const auto translations = clip.motion.translations(local);
  out.local_rotations.push_back(placement.rotation * rotations[0]);
  out.local_rotations.insert(out.local_rotations.end(), rotations.begin() + 1, rotations.end());
  out.local_translations_m.push_back(placement.apply(s * translations[0]));
  for (size_t i = 1; i < translations.size(); ++i) out.local_translations_m.push_back(s * translations[i]);
  ++out.frame_count;
}

void MotionAssembler::append_blend(int departure, const PreparedFloorTransform& w_departure, int arrival,
                                   const PreparedFloorTransform& w_arrival, double alpha, Motion& out) const {
  int local_d = 0, local_a = 0;
  const DatabaseClip& clip_d = clip_of(departure, &local_d);
  const DatabaseClip& clip_a = clip_of(arrival, &local_a);
  const double s_d = scale_[clip_d.skeleton], s_a = scale_[clip_a.skeleton];
  const auto rot_d = clip_d.motion.rotations(local_d), rot_a = clip_a.motion.rotations(local_a);
  const auto tr_d = clip_d.motion.translations(local_d), tr_a = clip_a.motion.translations(local_a);
  const double beta = 1.0 - alpha;
  const RootPose root = blend_root(departure, w_departure, arrival, w_arrival, alpha);
  out.local_rotations.push_back(root.rotation);
  for (size_t j = 1; j < rot_d.size(); ++j) out.local_rotations.push_back(rot_d[j].slerp(beta, rot_a[j]).normalized());
  out.local_translations_m.push_back(root.position);
  for (size_t i = 1; i < tr_d.size(); ++i) out.local_translations_m.push_back(alpha * s_d * tr_d[i] + beta * s_a * tr_a[i]);
  ++out.frame_count;
}

template <class OnFrame, class OnBlend>
void MotionAssembler::visit_edge(int edge_index, FloorTransform& placement, OnFrame on_frame, OnBlend on_blend) const {
  const GraphEdge& edge = graph_->edges[edge_index];
  const int from_frame = graph_->nodes[edge.from_node].frame;
  const PreparedFloorTransform departure(placement);
  if (!edge.transition) {
    for (int p = 0; p < edge.frame_count; ++p) on_frame(from_frame + p, departure);
    return;
  }
  const Transition& t = graph_->transitions[edge.transition_index];
  const int k = blend_frames(edge);
  const FloorTransform arrival = placement * transition_transform(t);
  const PreparedFloorTransform prepared_arrival(arrival);
  for (int p = 0; p < edge.frame_count; ++p) {
    on_blend(t.from_frame + p, departure, t.to_frame - k + 1 + p, prepared_arrival, blend_weight(p, k));
  }
  placement = arrival;
}

void MotionAssembler::append_edge(int edge, FloorTransform& placement, Motion& out) const {
  visit_edge(
      edge, placement, [&](int frame, const PreparedFloorTransform& w) { append_frame(frame, w, out); },
      [&](int d, const PreparedFloorTransform& wd, int a, const PreparedFloorTransform& wa, double alpha) {
        append_blend(d, wd, a, wa, alpha, out);
      });
}

void MotionAssembler::append_edge_roots(int edge, FloorTransform& placement, std::vector<RootPose>& out) const {
  visit_edge(
      edge, placement, [&](int frame, const PreparedFloorTransform& w) { out.push_back(root_pose(frame, w)); },
      [&](int d, const PreparedFloorTransform& wd, int a, const PreparedFloorTransform& wa, double alpha) {
        out.push_back(blend_root(d, wd, a, wa, alpha));
      });
}

void MotionAssembler::append_edge_contacts(int edge, std::span<const ContactMask> frame_contacts,
                                           std::vector<ContactMask>& out) const {
  FloorTransform placement;
  visit_edge(
      edge, placement, [&](int frame, const PreparedFloorTransform&) { out.push_back(frame_contacts[frame]); },
      [&](int d, const PreparedFloorTransform&, int a, const PreparedFloorTransform&, double alpha) {
        out.push_back(frame_contacts[FrameSource{d, a, alpha}.dominant()]);
      });
}

void MotionAssembler::append_edge_sources(int edge, std::vector<FrameSource>& out) const {
  FloorTransform placement;
  visit_edge(
      edge, placement, [&](int frame, const PreparedFloorTransform&) { out.push_back({frame, frame, 1.0}); },
      [&](int d, const PreparedFloorTransform&, int a, const PreparedFloorTransform&, double alpha) {
        out.push_back({d, a, alpha});
      });
}

Result<Motion> assemble_walk(const MotionDatabase& db, const MotionGraph& graph, const Walk& walk,
                             const FloorTransform& start, int target_skeleton) {
  if (auto status = check_walk(graph, walk); !status) return status.error();
  const int first_frame = graph.nodes[walk.start_node].frame;
  if (target_skeleton < 0) target_skeleton = db.clips[db.clip_of(first_frame)].skeleton;
  auto assembler = MotionAssembler::create(db, graph, target_skeleton);
  if (!assembler) return assembler.error();
  Motion out = assembler->empty_motion();
  size_t frames = walk.rest_frames.empty() ? 1 : walk.rest_frames.size();
  for (int e : walk.edges) frames += static_cast<size_t>(graph.edges[e].frame_count);
  out.local_rotations.reserve(frames * static_cast<size_t>(out.joint_count));
  out.local_translations_m.reserve(frames * static_cast<size_t>(out.translated_count));
  FloorTransform placement = start;
  for (int e : walk.edges) assembler->append_edge(e, placement, out);
  if (walk.rest_frames.empty()) assembler->append_frame(graph.nodes[walk.end_node(graph)].frame, placement, out);
  for (int f : walk.rest_frames) assembler->append_frame(f, placement, out);
  return out;
}

}  // namespace mg
