#include "motiongraph/synthesis/controller.h"

#include <algorithm>
#include <array>
#include <bit>
#include <chrono>
#include <future>
#include <system_error>
#include <limits>
#include <cmath>
#include <numbers>
#include <string>
#include <utility>

#include <fmt/format.h>

#include "motiongraph/graph/graph_from_candidates.h"
#include "motiongraph/motion/forward_kinematics.h"
#include "motiongraph/synthesis/steer_cost.h"
#include "motiongraph/synthesis/travelling_type.h"

namespace mg {

Status ControllerSettings::validate() const {
  auto refused = [](const std::string& what) { return Error{"", 0, "controller: " + what}; };
  if (auto s = check_horizon_and_commit(horizon_s, commit_s, "controller"); !s) return s;
  for (const auto& [value, what] : {std::pair{transition_penalty, "the transition penalty"},
                                    std::pair{bridge_penalty, "the bridge penalty"},
                                    std::pair{tag_penalty, "the tag penalty"},
                                    std::pair{time_budget_s, "the time budget"},
                                    std::pair{travel_mps, "the travel pace"},
                                    std::pair{travel_penalty, "the travel penalty"}}) {
    if (!(value >= 0.0) || !std::isfinite(value)) {
      return refused(fmt::format("{} must be finite and >= 0, not {:g}", what, value));
    }
  }
  if (!(tag_lookahead >= 0.0 && tag_lookahead <= 1.0)) {
    return refused(fmt::format("the tag lookahead must be from 0 to 1, not {:g}", tag_lookahead));
  }
  if (travel_mps > kMaxTravelMps || travel_penalty > kMaxTravelPenalty) {
    return refused(fmt::format("the travel pace must be at most {:g} m/s and its penalty at most {:g}, not {:g} "
                               "and {:g}",
                               kMaxTravelMps, kMaxTravelPenalty, travel_mps, travel_penalty));
  }
  if (max_expansions < 1) {
    return refused(fmt::format("the search budget (expansions) must be at least 1, not {}", max_expansions));
  }
  if (beam_width < 0 || beam_width > kMaxBeamWidth) {
    return refused(fmt::format("the beam width must be from 0 to {}, not {}", kMaxBeamWidth, beam_width));
  }
  if (start_node < -1) return refused(fmt::format("the start node must be >= 0, not {}", start_node));
  return heading_edit.validate();
}

Vec2 bearing_direction(double bearing_deg) {
  const double b = bearing_deg * std::numbers::pi / 180.0;
  return {std::sin(b), -std::cos(b)};
}

double direction_bearing(const Vec2& d) {
  double b = std::atan2(d.x(), -d.y()) * 180.0 / std::numbers::pi;
  return b < 0.0 ? b + 360.0 : b;
}

TagMask most_played_type(const SynthesisContext& context) {
  const MotionGraph& graph = *context.graph;
  const TagMask types = motion_type_tags(*context.db);
  std::array<int, 64> nodes{};
  for (int n = 0; n < graph.node_count(); ++n) {
    for (TagMask m = context.tracks.tags_of(graph.edge_offsets[n]).front() & types; m != 0; m &= m - 1) {
      ++nodes[static_cast<size_t>(std::countr_zero(m))];
    }
  }
  const auto most = std::max_element(nodes.begin(), nodes.end());
  return *most == 0 ? TagMask{0} : TagMask{1} << (most - nodes.begin());
}

int controller_start_node(const SynthesisContext& context, TagMask tag) {
  const MotionGraph& graph = *context.graph;
  if (tag == 0) tag = travelling_type(context);
  if (tag == 0) tag = most_played_type(context);
  if (tag == 0) return 0;
  for (int n = 0; n < graph.node_count(); ++n) {
    if ((context.tracks.tags_of(graph.edge_offsets[n]).front() & tag) != 0) return n;
  }
  return 0;
}

Result<Controller> Controller::create(const SynthesisContext& context, const ControllerSettings& settings,
                                      const ControlInput& first_input, const Vec2& at) {
  if (auto status = settings.validate(); !status) return status.error();
  const MotionGraph& graph = *context.graph;
  int start = settings.start_node;
  if (start >= graph.node_count()) return Error{"", 0, "controller: the start node does not exist"};
  if (!at.allFinite()) return Error{"", 0, "controller: the start position is not a finite point"};
  if (!first_input.direction.allFinite()) return Error{"", 0, "controller: the heading is not a finite direction"};
  if (start < 0) start = controller_start_node(context, first_input.tag);
  Controller controller(context, settings);
  controller.input_ = first_input;
  controller.state_.node = start;
  controller.state_.placement = context.placement_facing(start, at, first_input.direction);
  return controller;
}

bool Controller::rest_is_for_good() const {
  return resting_ && context_->graph->node_at_frame(rest_->last_frame) < 0 &&
         context_->rest_starts(rest_->last_frame).empty();
}

std::vector<FrameSource> decision_sources(const SynthesisContext& context, const ControllerDecision& decision) {
  std::vector<FrameSource> out = decision.start_frames;
  const std::vector<FrameSource> played = context.walk_sources(Walk{-1, decision.edges, decision.rest_frames});
  out.insert(out.end(), played.begin(), played.end());
  return out;
}

bool Controller::standing() const { return resting_ && ending_next_ >= ending_frames_.size(); }

ControllerDecision Controller::step(Motion& out) {
  using Clock = std::chrono::steady_clock;
  const auto begin = Clock::now();
  ControllerDecision decision;
  // Asked to move at rest: on from the node at the frame held once it holds it, or where there is
  // none, a start as soon as it stands still (the stopping clip's still tail is no wait: CMU 29's
  // lasts 1.7 s).
  const int on_node = resting_ ? context_->graph->node_at_frame(rest_->last_frame) : -1;
  if (!input_.rest && resting_ && !still() && take_back(out, decision)) {
    decision.search_seconds = std::chrono::duration<double>(Clock::now() - begin).count();
    return decision;
  }
  if (!input_.rest && standing() && on_node >= 0) {
    // On from the frame it holds: the graph's node there, placed as the frame is.
    state_.node = on_node;
    state_.placement = rest_placement_;
    const Vec3 held = context_->assembler.root_position(rest_->last_frame, rest_placement_);
    state_.last_root = Vec2(held.x(), held.z());
    state_.has_last = true;
    resting_ = false;
  } else if (!input_.rest && still() && on_node < 0 && start_off(out, decision)) {
    decision.search_seconds = std::chrono::duration<double>(Clock::now() - begin).count();
    return decision;
  }
  if (resting_ || (input_.rest && !context_->rest().empty())) {
    step_to_rest(out, decision);
    decision.search_seconds = std::chrono::duration<double>(Clock::now() - begin).count();
    return decision;
  }
  const MotionGraph& graph = *context_->graph;
  const double fps = context_->db->fps;
  HorizonSettings search;
  search.horizon_frames = std::max(1, static_cast<int>(std::lround(settings_.horizon_s * fps)));
  search.max_expansions = settings_.max_expansions;
  search.time_budget_s = settings_.time_budget_s;
  search.beam_width = settings_.beam_width;
  const SteerCost cost(*context_, input_, settings_, &state_);
  const HorizonResult best = horizon_search(graph, context_->tracks, state_, cost, search);
  decision.expansions = best.expansions;
  decision.budget_exhausted = best.budget_exhausted;
  const int commit_frames = std::max(1, static_cast<int>(std::lround(settings_.commit_s * fps)));
  std::vector<int> edges = best.edges;
  if (edges.empty()) edges.push_back(graph.edge_offsets[state_.node]);  // the clip piece onwards
  size_t committed = 0;
  for (int frames = 0; committed < edges.size() && frames < commit_frames; ++committed) {
    frames += graph.edges[edges[committed]].frame_count;
  }
  decision.search_seconds = std::chrono::duration<double>(Clock::now() - begin).count();
  play(std::span<const int>(edges).first(committed), edges, out, decision);
  decision.contacts = context_->edges_contacts(decision.edges);
  return decision;
}

void Controller::play(std::span<const int> committed, std::span<const int> planned, Motion& out,
                      ControllerDecision& decision) {
  const MotionGraph& graph = *context_->graph;
  int frames = 0;
  for (int e : committed) frames += graph.edges[e].frame_count;
  // The facings and roots the decision's walk plans from the first frame committed, unedited, as
  // far as the heading edit looks past the last committed (or as far as the walk goes).
  std::vector<Vec2> planned_facings, planned_roots;
  if (settings_.heading_edit.max_turn_deg_per_m > 0.0) {
    const std::vector<int> walk(planned.begin(), planned.end());
    const auto count = static_cast<size_t>(frames + edit_.half_window_frames());
    planned_facings = walk_facings(graph, context_->tracks, state_, walk, count);
    if (settings_.heading_edit.hold_travel) planned_roots = walk_roots(graph, context_->tracks, state_, walk, count);
  }
  const int first = out.frame_count;
  const SearchState before = state_;
  for (int e : committed) {
    FloorTransform placement = state_.placement;
    context_->assembler.append_edge(e, placement, out);
    state_ = advance(graph, context_->tracks, state_, e);
    decision.edges.push_back(e);
  }
  decision.frames += frames;
  if (settings_.heading_edit.max_turn_deg_per_m > 0.0 && frames > 0) {
    const FloorTransform move = edit_.apply(out, first, before.has_last ? &before.last_root : nullptr, planned_facings,
                                            planned_roots, input_.direction);
    state_.placement = move * state_.placement;
    state_.last_root = place(move, state_.last_root);
  }
}

Vec2 Controller::start_way(const RestStart& start) const {
  const MotionGraph& graph = *context_->graph;
  const FloorTransform lead = rest_placement_ * start.alignment;
  const int node_frame = graph.nodes[start.node].frame;
  const DatabaseClip& clip = context_->db->clips[graph.nodes[start.node].clip];
  const int ahead = std::min(clip.first_frame + clip.frame_count - 1,
                             node_frame + static_cast<int>(std::lround(kStartHeadingS * context_->db->fps)));
  const Vec3 from = context_->assembler.root_position(start.first_frame, lead);
  const Vec3 to = context_->assembler.root_position(ahead, lead);
  const Vec2 way(to.x() - from.x(), to.z() - from.z());
  return way.norm() > 1e-6 ? Vec2(way / way.norm()) : Vec2::Zero();
}

FloorTransform Controller::start_turn(const RestStart& start, const Vec2& pivot) const {
  if (settings_.heading_edit.max_turn_deg_per_m <= 0.0) return {};
  const Vec2 way = start_way(start);
  if (way.isZero()) return {};
  const double limit = kStartMaxTurnDeg * std::numbers::pi / 180.0;
  const double turn = std::clamp(yaw_between(way, input_.direction), -limit, limit);
  const Vec3 turned = FloorTransform{turn, 0.0, 0.0}.apply(Vec3(pivot.x(), 0.0, pivot.y()));
  return {turn, pivot.x() - turned.x(), pivot.y() - turned.z()};
}

const RestStart* Controller::choose_start(const std::vector<RestStart>& starts) const {
  const MotionGraph& graph = *context_->graph;
  // The choice (see the header): into the motion type asked for where any start is, near enough
  // the nearest, and heading the way asked.
  const TagMask wanted = input_.tag != 0 ? input_.tag : moving_types_;
  auto into_tag = [&](const RestStart& start) {
    return (context_->frame_tag(graph.nodes[start.node].frame) & wanted) != 0;
  };
  const bool by_tag = wanted != 0 && std::any_of(starts.begin(), starts.end(), into_tag);
  double nearest = std::numeric_limits<double>::infinity();
  for (const RestStart& start : starts) {
    if (!by_tag || into_tag(start)) nearest = std::min(nearest, start.rank_m);
  }
  const RestStart* chosen = nullptr;
  double best = std::numeric_limits<double>::infinity();
  for (const RestStart& start : starts) {
    if ((by_tag && !into_tag(start)) || start.rank_m > kStartSlack * nearest) continue;
    const double near = nearest > 0.0 ? start.rank_m / nearest - 1.0 : 0.0;
    const double score = near + (1.0 - start_way(start).dot(input_.direction));
    if (score < best) {
      best = score;
      chosen = &start;
    }
  }
  return chosen;  // (null: none within the slack of the nearest, not for finite ranks)
}

bool Controller::start_off(Motion& out, ControllerDecision& decision) {
  const std::vector<RestStart>& starts = context_->rest_starts(rest_->last_frame);
  const RestStart* chosen = choose_start(starts);
  if (chosen == nullptr) return false;
  const int held = ending_frames_[ending_next_ - 1];  // the frame it stands in: the last played
  const std::vector<int> departures(static_cast<size_t>(chosen->blend_frames), held);
  play_start(*chosen, departures, last_played_root(), false, out, decision);
  return true;
}

Vec2 Controller::last_played_root() const {
  if (ending_next_ == 0) return state_.last_root;
  const Vec3 root = context_->assembler.root_position(ending_frames_[ending_next_ - 1], rest_placement_);
  return {root.x(), root.z()};
}

void Controller::forget_rest() {
  taken_back_.push_back(state_.frames);
  resting_ = false;
  rest_frames_.pop_back();
  rest_endings_.pop_back();
  rest_ = rest_endings_.empty() ? nullptr : rest_endings_.back();
}

bool Controller::take_back(Motion& out, ControllerDecision& decision) {
  const MotionGraph& graph = *context_->graph;
  const int blend = std::max(2, static_cast<int>(std::lround(kStartBlendS * context_->db->fps)));
  // A node of the graph the stopping clip reaches within the blend's time, of the motion type asked
  // (or moving_types_): on to it, as captured. Not on a library without motion types, where nothing
  // makes the search from a node of a stop go anywhere (CMU 29 stood on at its node): a start leads
  // into motion that travels.
  const TagMask wanted = input_.tag != 0 ? input_.tag : moving_types_;
  for (size_t k = ending_next_; k < ending_frames_.size() && k <= ending_next_ + static_cast<size_t>(blend); ++k) {
    const int node = graph.node_at_frame(ending_frames_[k]);
    if (node < 0 || (context_->frame_tag(ending_frames_[k]) & wanted) == 0) continue;
    if (ending_frames_[k] >= rest_->rest_frame) break;  // (standing there: a start)
    play_rest(out, decision, static_cast<int>(k - ending_next_), false);
    state_.node = node;
    state_.placement = rest_placement_;
    state_.last_root = last_played_root();
    state_.has_last = state_.has_last || ending_next_ > 0;
    forget_rest();
    return decision.frames > 0;
  }
  // Else a start from the frames it is playing on.
  std::vector<int> coming;
  for (size_t k = ending_next_; k < ending_frames_.size() && coming.size() < static_cast<size_t>(blend); ++k) {
    coming.push_back(ending_frames_[k]);
  }
  if (coming.empty()) return false;
  coming.resize(static_cast<size_t>(blend), coming.back());
  const std::vector<RestStart> starts =
      find_starts_from(*context_->db, graph, context_->assembler, coming, kGoingMps);
  const RestStart* chosen = choose_start(starts);
  if (chosen == nullptr) return false;
  const Vec2 last = last_played_root();
  forget_rest();
  play_start(*chosen, coming, last, true, out, decision);
  return true;
}

void Controller::play_start(const RestStart& chosen, std::span<const int> departures, const Vec2& from,
                            bool under_way, Motion& out, ControllerDecision& decision) {
  const MotionGraph& graph = *context_->graph;
  const MotionAssembler& assembler = context_->assembler;
  const Vec3& axis = context_->tracks.forward_axis;
  // The frames blended from into the lead-in, then the lead-in on as captured to the node.
  const int node_frame = graph.nodes[chosen.node].frame;
  const FloorTransform lead = start_turn(chosen, from) * rest_placement_ * chosen.alignment;
  const PreparedFloorTransform w_from(rest_placement_), w_lead(lead);
  const int first = out.frame_count;
  for (int p = 0; p < chosen.blend_frames; ++p) {
    const double alpha = blend_weight(p, chosen.blend_frames);
    const int departure = departures[static_cast<size_t>(p)];
    assembler.append_blend(departure, w_from, chosen.first_frame + p, w_lead, alpha, out);
    decision.start_frames.push_back({departure, chosen.first_frame + p, alpha});
  }
  for (int f = chosen.first_frame + chosen.blend_frames; f < node_frame; ++f) {
    assembler.append_frame(f, w_lead, out);
    decision.start_frames.push_back({f, f, 1.0});
  }
  state_.placement = lead;
  if (settings_.heading_edit.max_turn_deg_per_m > 0.0) {
    // The plan: the start's frames as played, then its clip on from the node as far as the edit looks.
    std::vector<Vec2> facings, roots;
    auto plan = [&](const Quat& rotation, const Vec3& root) {
      facings.push_back(facing_on_floor(rotation, axis));
      if (settings_.heading_edit.hold_travel) roots.emplace_back(root.x(), root.z());
    };
    for (int f = first; f < out.frame_count; ++f) plan(out.rotations(f)[0], out.translations(f)[0]);
    const DatabaseClip& clip = context_->db->clips[graph.nodes[chosen.node].clip];
    for (int i = 0; i < edit_.half_window_frames(); ++i) {
      const int frame = std::min(node_frame + i, clip.first_frame + clip.frame_count - 1);
      const RootPose root = assembler.root_pose(frame, lead);
      plan(root.rotation, root.position);
    }
    state_.placement = edit_.apply(out, first, &from, facings, roots, input_.direction) * lead;
  }
  // Each frame's dominant source's contacts, a foot's gap where the weights cross filled.
  decision.contacts = context_->sources_contacts(decision.start_frames);
  fill_contact_gaps(decision.contacts, FootContactSettings{}.max_gap_frames(context_->db->fps));
  Vec2 at = from;
  for (int f = first; f < out.frame_count; ++f) {
    const Vec2 root(out.translations(f)[0].x(), out.translations(f)[0].z());
    state_.arc_m += (root - at).norm();
    at = root;
  }
  starts_.push_back({state_.frames, chosen, under_way});
  state_.node = chosen.node;
  state_.last_root = at;
  state_.has_last = true;
  state_.frames += out.frame_count - first;
  decision.frames += out.frame_count - first;
  resting_ = false;
}

void Controller::play_ending(Motion& out, ControllerDecision& decision, int& frames, size_t until) {
  const std::vector<ContactMask>& contacts = context_->frame_contacts;  // (empty: the feet not known)
  const PreparedFloorTransform placement(rest_placement_);
  for (; frames > 0 && ending_next_ < until; --frames) {
    const bool pivoting = ending_next_ >= ending_pivot_ && ending_next_ < ending_turned_;
    const int frame = ending_frames_[ending_next_++];
    context_->assembler.append_frame(frame, placement, out);
    decision.rest_frames.push_back(frame);
    if (!contacts.empty()) {
      decision.contacts.push_back(contacts[static_cast<size_t>(frame)] &
                                  static_cast<ContactMask>(pivoting ? ~pivot_bits_ : 0xff));
    }
    ++decision.frames;
    ++state_.frames;
  }
}

void Controller::play_rest(Motion& out, ControllerDecision& decision, int frames, bool hold) {
  const std::vector<ContactMask>& contacts = context_->frame_contacts;
  const int first = out.frame_count;
  const size_t from = ending_next_;
  play_ending(out, decision, frames, ending_turned_);
  if (ending_next_ > from) edit_ending(out, first, from);
  play_ending(out, decision, frames, ending_frames_.size());
  if (ending_next_ > from && ending_next_ == ending_frames_.size()) held_pose_ = out.slice(out.frame_count - 1, 1);
  for (; frames > 0 && hold; --frames) {
    out.local_rotations.insert(out.local_rotations.end(), held_pose_.local_rotations.begin(),
                               held_pose_.local_rotations.end());
    out.local_translations_m.insert(out.local_translations_m.end(), held_pose_.local_translations_m.begin(),
                                    held_pose_.local_translations_m.end());
    ++out.frame_count;
    decision.rest_frames.push_back(rest_->last_frame);
    if (!contacts.empty()) decision.contacts.push_back(contacts[static_cast<size_t>(rest_->last_frame)]);
    ++decision.frames;
    ++state_.frames;
  }
}

void Controller::step_to_rest(Motion& out, ControllerDecision& decision) {
  const MotionGraph& graph = *context_->graph;
  const int commit_frames = std::max(1, static_cast<int>(std::lround(settings_.commit_s * context_->db->fps)));
  // Up to a decision's worth of frames at rest (a game shows each decision's frames as they come).
  if (resting_) {
    play_rest(out, decision, commit_frames, ending_next_ >= ending_frames_.size());
    return;
  }
  if (rest_cost_.empty()) {
    rest_cost_ = cost_to_rest(graph, context_->rest(), settings_.transition_penalty, settings_.bridge_penalty);
  }
  // Down the costs to rest, for as long as a decision commits.
  RestRoute way = rest_route(graph, context_->rest(), rest_cost_, state_.node, settings_.transition_penalty,
                             settings_.bridge_penalty, commit_frames);
  std::vector<int>& route = way.edges;
  const RestEnding* ending = way.ending;
  if (route.empty() && ending == nullptr) {  // no way to rest from here: play on as the graph does
    route.push_back(graph.edge_offsets[state_.node]);
  }
  play(route, route, out, decision);
  decision.contacts = context_->edges_contacts(decision.edges);
  if (ending == nullptr) return;
  resting_ = true;
  rest_ = ending;
  moving_types_ = context_->frame_tag(graph.nodes[ending->node].frame) & motion_type_tags(*context_->db);
  if (moving_types_ == 0) moving_types_ = most_played_type(*context_);
  rest_placement_ = state_.placement;
  rest_frames_.push_back(state_.frames + ending->frames_to_rest(graph));
  rest_endings_.push_back(ending);
  // The starts from the frame it will hold, found in the background while it stops (a second or
  // more), not in the decision that first starts off (the 8-subject library's take 0.1 s).
  if (graph.node_at_frame(ending->last_frame) < 0) {
    try {
      starts_found_ = std::async(std::launch::async, [context = context_, frame = ending->last_frame] {
                        context->rest_starts(frame);
                      }).share();
    } catch (const std::system_error&) {
      // (no thread to spare: found when first asked for)
    }
  }
  ending_frames_ = ending->frames(graph);
  ending_next_ = 0;
  // Where each foot makes its last plant. Turning about the root on from the first, the clean-up
  // would hold that foot where it planted while the body turned above it, and the stance held for
  // good would twist (ankles 3 cm apart for 8 on subject 16 asked to turn 90 degrees right as it
  // stopped): from there the body turns about that foot's ankle (a pivot), the clean-up letting it
  // turn (its contacts cleared), until the other plants too; then it turns no more.
  ending_turned_ = ending_frames_.size();
  ending_pivot_ = ending_frames_.size();
  pivot_ankle_ = -1;
  pivot_bits_ = 0;
  pivot_pinned_ = false;
  if (!context_->frame_contacts.empty()) {
    const ContactMask standing = context_->frame_contacts[static_cast<size_t>(ending_frames_.back())];
    size_t planted[2] = {ending_frames_.size(), ending_frames_.size()};  // per foot: left, right
    for (const FootSide side : {FootSide::kLeft, FootSide::kRight}) {
      for (const FootPart part : {FootPart::kAnkle, FootPart::kToe}) {
        const ContactMask mask = contact_bit(side, part);
        if ((standing & mask) == 0) continue;
        size_t start = ending_frames_.size() - 1;
        while (start > 0 && (context_->frame_contacts[static_cast<size_t>(ending_frames_[start - 1])] & mask) != 0) {
          --start;
        }
        size_t& foot = planted[side == FootSide::kLeft ? 0 : 1];
        foot = std::min(foot, start);
      }
    }
    const int first_foot = planted[0] <= planted[1] ? 0 : 1;
    ending_pivot_ = planted[first_foot];
    ending_turned_ = std::max(planted[0], planted[1]);
    const Foot& pivot = first_foot == 0 ? context_->feet.left : context_->feet.right;
    pivot_ankle_ = pivot.ankle;
    const FootSide side = first_foot == 0 ? FootSide::kLeft : FootSide::kRight;
    pivot_bits_ = static_cast<ContactMask>(contact_bit(side, FootPart::kAnkle) | contact_bit(side, FootPart::kToe));
    // Both feet down together, a foot not known, or no heading edit: no pivot (the contacts as
    // captured), the turning stops there.
    if (pivot_ankle_ < 0 || settings_.heading_edit.max_turn_deg_per_m <= 0.0) ending_turned_ = ending_pivot_;
  }
  play_rest(out, decision, std::max(0, commit_frames - decision.frames), false);
}

// The stopping clip's frames played [from, ending_next_) turned by the heading edit as the way
// there was: a turn asked just before rest is carried on while the character still travels (the
// edit turns with the root's travel, so it ends as the clip slows), and it stands facing the way
// asked as far as the last steps allow; from the first foot's last plant on, about its ankle.
void Controller::edit_ending(Motion& out, int first, size_t from) {
  if (settings_.heading_edit.max_turn_deg_per_m <= 0.0) return;
  const MotionAssembler& assembler = context_->assembler;
  // The plan: the clip's frames from `from` on as far as the edit looks, then its last frame held.
  const size_t count = (ending_next_ - from) + static_cast<size_t>(edit_.half_window_frames());
  std::vector<Vec2> facings, roots;
  facings.reserve(count);
  for (size_t i = from; i < from + count; ++i) {
    const int frame = i < ending_frames_.size() ? ending_frames_[i] : rest_->last_frame;
    facings.push_back(facing_on_floor(assembler.root_rotation(frame, rest_placement_), context_->tracks.forward_axis));
    if (settings_.heading_edit.hold_travel) {
      const Vec3 root = assembler.root_position(frame, rest_placement_);
      roots.emplace_back(root.x(), root.z());
    }
  }
  FloorTransform move = edit_.apply(out, first, state_.has_last ? &state_.last_root : nullptr, facings, roots,
                                    input_.direction);
  // From the first foot's last plant on, the frames are moved on the floor so that its ankle stays
  // where it planted: the turn pivots on it.
  if (pivot_ankle_ >= 0) {
    const Skeleton& skeleton = assembler.skeleton();
    for (int f = std::max(first, first + static_cast<int>(ending_pivot_) - static_cast<int>(from));
         f < out.frame_count; ++f) {
      const Vec3 ankle = world_positions(skeleton, out.slice(f, 1))[static_cast<size_t>(pivot_ankle_)];
      if (!pivot_pinned_) {
        pivot_at_ = Vec2(ankle.x(), ankle.z());
        pivot_pinned_ = true;
      }
      const Vec2 shift = pivot_at_ - Vec2(ankle.x(), ankle.z());
      Vec3& root = out.translations(f)[0];
      root.x() += shift.x();
      root.z() += shift.y();
      if (f == out.frame_count - 1) {
        move.x_m += shift.x();
        move.z_m += shift.y();
      }
    }
  }
  rest_placement_ = move * rest_placement_;
  state_.placement = rest_placement_;
  const Vec3& last = out.translations(out.frame_count - 1)[0];
  state_.last_root = Vec2(last.x(), last.z());
  state_.has_last = true;
}

}  // namespace mg
