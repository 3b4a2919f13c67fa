#include "studio/synthesis_service.h"

#include <algorithm>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "motiongraph/database/database_doubts.h"
#include "motiongraph/export/bvh_writer.h"
#include "motiongraph/export/motion_file.h"
#include "motiongraph/motion/root_motion.h"
#include "motiongraph/export/matrix_png.h"
#include "motiongraph/graph/candidates.h"

namespace mg::studio {

Result<std::unique_ptr<SynthesisService>> SynthesisService::load(const std::string& graph_path) {
  auto graph = LoadedGraph::load(graph_path);
  if (!graph) return graph.error();
  return create(std::move(*graph), graph_path);
}

std::unique_ptr<SynthesisService> SynthesisService::create(std::unique_ptr<LoadedGraph> graph, std::string graph_path) {
  std::unique_ptr<SynthesisService> service(new SynthesisService());
  service->path_ = std::move(graph_path);
  service->graph_ = std::move(graph);
  return service;
}

int SynthesisService::store_recorded(std::shared_ptr<Recorded> recorded) {
  std::lock_guard lock(mutex_);
  return store_recorded_locked(std::move(recorded));
}

int SynthesisService::store_recorded_locked(std::shared_ptr<Recorded> recorded) {
  const int id = next_id_++;
  results_[id] = std::move(recorded);
  long long frames = 0;
  for (const auto& [key, kept] : results_) frames += kept->kept_frames;
  // The oldest go first, but neither a live session's recording nor the one just stored.
  for (auto it = results_.begin();
       it != results_.end() && (static_cast<int>(results_.size()) > kMaxResults || frames > kMaxKeptFrames);) {
    if (it->first == id || sessions_.contains(it->first)) {
      ++it;
      continue;
    }
    frames -= it->second->kept_frames;
    it = results_.erase(it);
  }
  return id;
}

int SynthesisService::store_result(Motion motion) {
  auto recorded = std::make_shared<Recorded>();
  recorded->kept_frames = motion.frame_count;
  recorded->motion = std::move(motion);
  return store_recorded(std::move(recorded));
}

bool SynthesisService::has_result(int result) const {
  std::lock_guard lock(mutex_);
  return results_.contains(result);
}

std::optional<std::string> SynthesisService::result_file(int result, FileFormat format, bool root_motion,
                                                         bool figure) const {
  std::shared_ptr<Recorded> recorded;
  {
    std::lock_guard lock(mutex_);
    auto it = results_.find(result);
    if (it == results_.end()) return std::nullopt;
    recorded = it->second;
  }
  Motion motion;
  {
    std::lock_guard lock(recorded->mutex);
    motion = recorded->motion;
  }
  Skeleton skeleton = context().assembler.skeleton();
  if (root_motion) {
    auto added = add_root_motion(skeleton, motion, context().tracks.forward_axis, RootMotionSettings{});
    if (!added) return std::nullopt;  // a recorded motion's root always travels
    skeleton = std::move(added->skeleton);
    motion = std::move(added->motion);
  }
  if (format == FileFormat::kBvh) return write_bvh(skeleton, motion, BvhWriteSettings{});
  // The animation is named as the file downloads.
  const ExportAnimation animation{fmt::format("motiongraph-{}", result), &motion};
  const char* ext = format == FileFormat::kGlb ? ".glb" : format == FileFormat::kGltf ? ".gltf" : ".fbx";
  auto bytes = scene_bytes(ext, skeleton, std::span(&animation, 1), figure);
  if (!bytes) return std::nullopt;  // a recorded motion always fits the skeleton it was played on
  return std::move(*bytes);
}

Result<SynthesizedMotion> SynthesisService::walk(const WalkRequest& request) {
  const MotionGraph& graph = file().graph;
  if (request.from < 0 || request.from >= graph.node_count() || request.to < 0 || request.to >= graph.node_count()) {
    return Error{"", 0, fmt::format("nodes are 0..{}", graph.node_count() - 1)};
  }
  WalkSearchSettings settings;
  settings.cost = request.cost;
  settings.seed = request.seed;
  settings.min_frames = request.min_frames;
  settings.max_expansions = kWalkExpansions;
  settings.budget_advice = "ask for fewer frames (min_frames) or another pair of nodes";
  if (auto s = settings.validate(); !s) return s.error();
  auto found = find_walk(graph, request.from, request.to, settings);
  if (!found) return found.error();
  const FloorTransform start = context().placement_facing(request.from, Vec2::Zero(), Vec2(0.0, -1.0));
  auto motion = assemble_walk(file().database, graph, found->walk, start, context().assembler.target_skeleton());
  if (!motion) return motion.error();
  SynthesizedMotion out;
  auto contacts = played_contacts(found->walk, motion->frame_count);
  if (!contacts) return contacts.error();
  auto cleaned = clean_up(request.cleanup, *contacts, *motion);
  if (!cleaned) return cleaned.error();
  out.cleaned = *cleaned;
  out.contacts = std::move(*contacts);
  out.walk = found->walk;
  out.motion = std::move(*motion);
  out.transitions = found->walk.transition_count(graph);
  out.result = store_result(out.motion);
  return out;
}

Result<SynthesizedPath> SynthesisService::path(const FloorPath& path, const PathSynthesisSettings& settings,
                                               bool cleanup) const {
  if (auto s = settings.validate(); !s) return s.error();
  auto result = synthesize_path(context(), path, settings);
  if (!result) return result.error();
  SynthesizedPath out;
  out.synthesis = std::move(*result);
  auto contacts = played_contacts(out.synthesis.walk, out.synthesis.motion.frame_count);
  if (!contacts) return contacts.error();
  auto cleaned = clean_up(cleanup, *contacts, out.synthesis.motion);
  if (!cleaned) return cleaned.error();
  out.cleaned = *cleaned;
  out.contacts = std::move(*contacts);
  return out;
}

Result<std::vector<ContactMask>> SynthesisService::played_contacts(const Walk& walk, int frames) const {
  std::vector<ContactMask> contacts = context().walk_contacts(walk);
  if (contacts.empty()) return contacts;  // the graph's feet were not found
  if (static_cast<int>(contacts.size()) < frames) {
    return Error{"", 0, fmt::format("the walk plays {} frames, the motion has {}", contacts.size(), frames)};
  }
  contacts.resize(static_cast<size_t>(frames));
  return contacts;
}

Result<bool> SynthesisService::clean_up(bool asked, std::span<const ContactMask> contacts, Motion& motion) const {
  if (!asked) return false;
  auto cleanup = context().foot_cleanup({});
  if (!cleanup) return false;  // the graph's feet were not found
  if (auto s = cleanup->clean(motion, 0, contacts); !s) return s.error();
  return true;
}

namespace {

// The session stepped (or created) least recently; `sessions` is not empty.
template <class Sessions>
auto least_recently_used(Sessions& sessions) {
  return std::min_element(sessions.begin(), sessions.end(), [](const auto& a, const auto& b) {
    return a.second->last_used < b.second->last_used;
  });
}

}  // namespace

Status SessionLimits::validate() const {
  if (max_sessions < 1 || max_sessions > 1000) {
    return Error{"", 0, fmt::format("the sessions at most must be from 1 to 1000, not {}", max_sessions)};
  }
  if (!(busy_s >= 0.0 && busy_s <= 3600.0)) {
    return Error{"", 0, fmt::format("a session's time in use must be from 0 to 3600 s, not {:g}", busy_s)};
  }
  return Ok{};
}

Status SynthesisService::set_session_limits(const SessionLimits& limits) {
  if (Status valid = limits.validate(); !valid) return valid;
  std::lock_guard lock(mutex_);
  limits_ = limits;
  return Ok{};
}

SessionLimits SynthesisService::session_limits() const {
  std::lock_guard lock(mutex_);
  return limits_;
}

bool SynthesisService::sessions_all_busy() const {
  if (static_cast<int>(sessions_.size()) < limits_.max_sessions) return false;
  const auto oldest = least_recently_used(sessions_);
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - oldest->second->stepped_at).count() <
         limits_.busy_s;
}

Error SynthesisService::sessions_busy_error() const {
  return Error{"", 0,
               fmt::format("the studio steers at most {} sessions at once, and all were created or stepped within "
                           "the last {:g} s: stop steering in another tab, or try again (serve --max-sessions "
                           "raises the limit)",
                           limits_.max_sessions, limits_.busy_s),
               ErrorKind::kBusy};
}

Result<SteerSessionStart> SynthesisService::create_session(const SteeringControl& control, bool cleanup) {
  {
    // Refused before any work when all are in use. Nothing is evicted yet: the session may not
    // be made (a bad control).
    std::lock_guard lock(mutex_);
    if (sessions_all_busy()) return sessions_busy_error();
  }
  auto session = std::make_shared<Session>(context());
  auto input = session->controls.input(control, "the control");
  if (!input) return input.error();
  // The controller's defaults: an expansion budget (well under a millisecond a decision, but
  // for the first asking for each tag, which prices the way to it: a few milliseconds on an
  // 8-subject graph) and no wall-clock budget, so that a loaded machine or a slow build steers
  // the same way.
  auto controller = Controller::create(context(), ControllerSettings{}, *input);
  if (!controller) return controller.error();
  session->controller = std::make_unique<Controller>(std::move(*controller));
  if (cleanup) {
    if (auto foot_cleanup = context().foot_cleanup({}); foot_cleanup) session->cleanup = std::move(*foot_cleanup);
  }
  session->recorded = std::make_shared<Recorded>();
  session->recorded->motion = context().assembler.empty_motion();
  session->recorded->kept_frames = kMaxRecordedFrames;
  const std::vector<std::string> session_warnings = session->controls.warnings();
  // Checked again where the session goes in, under the same lock: sessions made at the same time
  // all passed the check above, and the last of them evicted one made a moment before (a 404 on
  // its first step). The least recently stepped goes only when it is idle.
  std::lock_guard lock(mutex_);
  if (sessions_all_busy()) return sessions_busy_error();
  while (static_cast<int>(sessions_.size()) >= limits_.max_sessions) sessions_.erase(least_recently_used(sessions_));
  const int id = store_recorded_locked(session->recorded);
  session->last_used = ++clock_;
  session->stepped_at = std::chrono::steady_clock::now();
  sessions_[id] = std::move(session);
  return SteerSessionStart{id, session_warnings};
}

Result<SteerStepResult> SynthesisService::step_session(int id, const SteeringControl& control, int min_frames) {
  std::shared_ptr<Session> session;
  {
    std::lock_guard lock(mutex_);
    auto it = sessions_.find(id);
    if (it == sessions_.end()) return Error{"", 0, fmt::format("no steering session {} (it may have expired)", id)};
    session = it->second;
    session->last_used = ++clock_;
    session->stepped_at = std::chrono::steady_clock::now();
  }
  std::lock_guard lock(session->mutex);
  const size_t said = session->controls.warnings().size();
  auto input = session->controls.input(control, "the control");
  if (!input) return input.error();
  if (turns_at_rest(*input, *session->controller)) session->controls.turn_at_rest("the control");
  session->controller->set_input(*input);
  SteerStepResult out;
  const std::vector<std::string>& said_all = session->controls.warnings();
  out.warnings.assign(said_all.begin() + static_cast<long>(said), said_all.end());
  out.motion = context().assembler.empty_motion();
  out.first_frame = session->frames;
  const size_t starts_before = session->controller->starts().size();
  do {
    const int first_new = out.motion.frame_count;
    const ControllerDecision decision = session->controller->step(out.motion);
    const std::vector<ContactMask>& contacts = decision.contacts;
    if (session->cleanup) {
      if (auto s = session->cleanup->clean(out.motion, first_new, contacts); !s) return s.error();
    }
    out.contacts.insert(out.contacts.end(), contacts.begin(), contacts.end());
    out.search_seconds += decision.search_seconds;
    out.transitions += decision_transitions(file().graph, decision);
    out.bridges += count_bridges(file().graph, decision.edges);
    if (decision.frames == 0) break;
  } while (out.motion.frame_count < min_frames);
  session->frames += out.motion.frame_count;
  const std::vector<StartTaken>& starts = session->controller->starts();
  out.starts.assign(starts.begin() + static_cast<long>(starts_before), starts.end());
  if (const RestEnding* ending = session->controller->rest_ending(); ending != nullptr) {
    out.rest_s = static_cast<double>(session->controller->rest_frame()) / context().db->fps;
    out.rest_clip = file().database.clips[static_cast<size_t>(file().database.clip_of(ending->last_frame))].name;
    out.resting = session->controller->resting();
    out.standing = session->controller->still();
    out.rest_for_good = session->controller->rest_is_for_good();
  }
  session->transitions += out.transitions;
  out.session_transitions = session->transitions;
  session->bridges += out.bridges;
  out.session_bridges = session->bridges;
  // The recording: the session's first kMaxRecordedFrames frames, one after another (a step that
  // does not fit whole gives what fits, and later steps nothing).
  std::lock_guard record(session->recorded->mutex);
  Motion& recorded = session->recorded->motion;
  const int fits = std::min(out.motion.frame_count, kMaxRecordedFrames - recorded.frame_count);
  if (fits > 0) {
    const Motion part = out.motion.slice(0, fits);
    recorded.local_rotations.insert(recorded.local_rotations.end(), part.local_rotations.begin(),
                                    part.local_rotations.end());
    recorded.local_translations_m.insert(recorded.local_translations_m.end(), part.local_translations_m.begin(),
                                         part.local_translations_m.end());
    recorded.frame_count += fits;
  }
  return out;
}

Result<std::string> SynthesisService::distance_png() const {
  std::call_once(picture_once_, [this] {
    picture_ = [this]() -> Result<std::string> {
      const CandidateSearch& stored = file().candidates;
      const int frames = file().database.frame_count();
      if (stored.picture_side < 1 ||
          stored.picture.size() != static_cast<size_t>(stored.picture_side) * stored.picture_side) {
        return Error{path_, 0, "the graph file holds no distance picture"};
      }
      const MinMatrix picture = coarsen_min_matrix(
          MinMatrixView{stored.picture, stored.picture_side, stored.picture_block}, frames, kPictureSide);
      std::vector<int> clip_starts;
      for (const DatabaseClip& clip : file().database.clips) clip_starts.push_back(clip.first_frame);
      MatrixPngSettings png;
      png.max_side_px = kPictureSide;
      return matrix_png(picture.view(), clip_starts, {}, png);
    }();
  });
  return *picture_;
}

const std::vector<std::vector<std::string>>& SynthesisService::clip_doubts() const {
  std::call_once(doubts_once_, [this] {
    std::vector<std::vector<std::string>> doubts;  // assigned whole: an exception leaves none half made
    for (const DoubtedClip& clip : database_clip_doubts(file().database)) doubts.push_back(clip.doubts.phrases());
    clip_doubts_ = std::move(doubts);
  });
  return clip_doubts_;
}

const std::vector<std::string>& SynthesisService::clip_mirror_of() const {
  std::call_once(mirror_of_once_, [this] {
    std::vector<std::string> of(file().database.clips.size());
    const nlohmann::json report = nlohmann::json::parse(file().report_json, nullptr, /*allow_exceptions=*/false);
    if (report.is_object() && report.contains("clips") && report["clips"].is_array()) {
      const nlohmann::json& clips = report["clips"];
      for (size_t c = 0; c < of.size() && c < clips.size(); ++c) {
        const auto it = clips[c].find("mirror_of");
        if (it != clips[c].end() && it->is_string()) of[c] = it->get<std::string>();
      }
    }
    clip_mirror_of_ = std::move(of);
  });
  return clip_mirror_of_;
}

int SynthesisService::picture_block() const {
  const CandidateSearch& stored = file().candidates;
  const int side = std::max(stored.picture_side, 1);
  return std::max(stored.picture_block, 1) * min_matrix_block(side, kPictureSide);
}

}  // namespace mg::studio
