// The studio's synthesis on one loaded graph (walk, path and interactive steering), shared by
// every request the server answers at once. The graph and its synthesis context are read-only
// after loading; results kept for download and the steering sessions (each with its own
// Controller) are guarded, so every member function may be called from any thread.
//
// Bounds: at most kMaxResults results are kept, of at most kMaxKeptFrames frames in all (the
// oldest go first, but not a live steering session's recording, which goes when its session
// does), at most SessionLimits::max_sessions steering sessions live at once (a new one takes the
// place of the least recently stepped, unless that was stepped within SessionLimits::busy_s: the
// new one is refused, ErrorKind::kBusy, rather than a client steering now losing its session),
// and a session records its first kMaxRecordedFrames frames for download (it keeps steering
// after that).
#pragma once

#include <chrono>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "motiongraph/evaluation/steering_controls.h"
#include "motiongraph/graph/graph_file.h"
#include "motiongraph/synthesis/controller.h"
#include "motiongraph/synthesis/loaded_graph.h"
#include "motiongraph/synthesis/path_synthesis.h"
#include "motiongraph/synthesis/walk.h"
#include "motiongraph/synthesis/walk_search.h"

namespace mg::studio {

struct WalkRequest {
  int from = 0;
  int to = 0;
  int min_frames = 0;
  WalkCost cost = WalkCost::kQuality;
  std::uint64_t seed = 1;
  bool cleanup = true;  // the foot clean-up (synthesis/foot_cleanup.h)
};

struct SynthesizedMotion {
  int result = 0;   // id for result_file()
  Motion motion;
  Walk walk;
  int transitions = 0;  // transition edges the walk took
  bool cleaned = false;  // the foot clean-up ran (asked, and the graph's feet were found)
  // Per frame of motion, the contacts it carries from its database frame (the ones the
  // clean-up holds); empty when the graph's feet were not found.
  std::vector<ContactMask> contacts;
};

struct SynthesizedPath {
  PathSynthesisResult synthesis;
  bool cleaned = false;  // as above
  std::vector<ContactMask> contacts;  // as above
};

struct SteerStepResult {
  Motion motion;    // the frames this step appended
  long long first_frame = 0;  // index of its first frame in the session's motion
  double search_seconds = 0.0;
  int transitions = 0;           // transition edges this step committed, and its start from rest (a blend)
  int session_transitions = 0;   // and the session so far
  int bridges = 0;               // of this step's transitions, the bridges (GraphEdge::bridge)
  int session_bridges = 0;       // and the session's
  std::vector<ContactMask> contacts;  // per frame of motion, as above
  // Once the character has come to rest (controller.h): the session's second from which it last
  // stood still and the clip whose end it stood at; -1 and "" before.
  double rest_s = -1.0;
  std::string rest_clip;
  bool resting = false;        // on its way to rest, or at it (Controller::resting)
  bool standing = false;       // standing still at rest now (Controller::still)
  bool rest_for_good = false;  // with no way on from it (Controller::rest_is_for_good)
  std::vector<StartTaken> starts;  // the starts from rest this step took (Controller::starts)
  // What this step's control asks that the graph cannot give, said once a session
  // (evaluation/steering_controls.h).
  std::vector<std::string> warnings;
};

struct SessionLimits {
  int max_sessions = 16;
  // A session stepped within this many seconds is in use: a new session does not take its place
  // (a steering client steps about 5 times a second; 0: the least recently stepped always goes).
  double busy_s = 10.0;

  Status validate() const;
};

struct SteerSessionStart {
  int id = 0;  // the session's, also the id of the result recording its motion
  std::vector<std::string> warnings;  // as SteerStepResult's, of the first control
};

class SynthesisService {
 public:
  static constexpr int kMaxResults = 32;
  static constexpr int kMaxRecordedFrames = 30 * 60 * 2;  // 2 minutes at 30 fps
  // Results' frames kept in all (a session's recording counts as kMaxRecordedFrames): a path's
  // may run to tens of thousands of frames, tens of MB each.
  static constexpr long long kMaxKeptFrames = 150000;
  static constexpr long long kWalkExpansions = 500000;     // a walk's search budget (the CLI's is 4x)

  // Loads a .mgraph file and sets up synthesis on it.
  static Result<std::unique_ptr<SynthesisService>> load(const std::string& graph_path);
  // Serves a graph already loaded (or built in process); `graph_path` names it in errors.
  static std::unique_ptr<SynthesisService> create(std::unique_ptr<LoadedGraph> graph, std::string graph_path);

  const std::string& graph_path() const { return path_; }
  const GraphFile& file() const { return graph_->file(); }
  const SynthesisContext& context() const { return graph_->context(); }

  Result<SynthesizedMotion> walk(const WalkRequest& request);
  // Path synthesis, its motion cleaned (foot clean-up) when `cleanup` and the graph has feet;
  // the caller stores the motion (store_result) when it keeps it.
  Result<SynthesizedPath> path(const FloorPath& path, const PathSynthesisSettings& settings = {},
                               bool cleanup = true) const;

  // A steering session starting at the origin facing the control's heading, its frames cleaned as
  // they are committed when `cleanup` and the graph has feet; ErrorKind::kBusy when the sessions
  // are at their limit and all in use (SessionLimits).
  Result<SteerSessionStart> create_session(const SteeringControl& control, bool cleanup = true);
  // The bounds on steering sessions (default SessionLimits{}); checked by validate().
  Status set_session_limits(const SessionLimits& limits);
  SessionLimits session_limits() const;
  // Sets the control and appends at least min_frames frames (one decision or more).
  Result<SteerStepResult> step_session(int session, const SteeringControl& control, int min_frames);

  // A result as a file: BVH text, binary glTF, glTF as JSON (its buffer embedded) or binary FBX
  // (with its stick figure unless `figure` is false), with a root-motion joint above the root when
  // asked (motion/root_motion.h, default settings); nothing when there is no such result (any more).
  enum class FileFormat { kBvh, kGlb, kGltf, kFbx };
  std::optional<std::string> result_file(int result, FileFormat format = FileFormat::kBvh, bool root_motion = false,
                                         bool figure = true) const;
  // Stores a motion for download and returns its id.
  int store_result(Motion motion);
  // Whether result_file() can still give that result.
  bool has_result(int result) const;

  // The distance picture (PNG bytes, at most kPictureSide pixels a side, picture_block()
  // frames per pixel): the block minima the graph file stores, made smaller to the block a
  // multiple of theirs (export/matrix_png.h: coarsen_min_matrix), drawn on first use and kept.
  // Fails when the file holds no picture.
  static constexpr int kPictureSide = 512;
  Result<std::string> distance_png() const;
  // Frames per pixel of the picture along each axis (it is ceil(frames / block) pixels a side).
  int picture_block() const;

  // What looks wrong with each database clip as read (motion/clip_doubts.h: its size, floor,
  // feet or clock), the phrases info gives; worked out on first use and kept.
  const std::vector<std::vector<std::string>>& clip_doubts() const;
  // Per database clip, the clip it mirrors (database_loader.h DatabaseSettings::mirror), or "":
  // from the build report the graph file stores (its clips' mirror_of); read on first use and kept.
  const std::vector<std::string>& clip_mirror_of() const;

 private:
  struct Recorded {
    mutable std::mutex mutex;
    Motion motion;
    long long kept_frames = 0;  // what it counts against kMaxKeptFrames (set when stored)
  };
  struct Session {
    explicit Session(const SynthesisContext& context) : controls(context) {}
    std::mutex mutex;
    SteeringControls controls;  // its controls' inputs, and what they asked that the graph cannot give
    std::unique_ptr<Controller> controller;
    std::optional<FootCleanup> cleanup;
    std::shared_ptr<Recorded> recorded;
    long long frames = 0;
    int transitions = 0;
    int bridges = 0;
    long long last_used = 0;
    std::chrono::steady_clock::time_point stepped_at;  // created, or last stepped
  };
  SynthesisService() = default;
  // The contacts of the first `frames` frames assemble_walk() plays for `walk` (none without
  // feet).
  Result<std::vector<ContactMask>> played_contacts(const Walk& walk, int frames) const;
  // Cleans a motion with its contacts when asked and the graph's feet were found; says
  // whether it did.
  Result<bool> clean_up(bool asked, std::span<const ContactMask> contacts, Motion& motion) const;
  int store_recorded(std::shared_ptr<Recorded> recorded);
  int store_recorded_locked(std::shared_ptr<Recorded> recorded);  // with mutex_ held
  // With mutex_ held: at the limit, and the least recently stepped session was stepped (or
  // created) within busy_s; the error that refuses a new session then.
  bool sessions_all_busy() const;
  Error sessions_busy_error() const;

  std::string path_;
  std::unique_ptr<LoadedGraph> graph_;

  mutable std::mutex mutex_;  // guards the members below
  int next_id_ = 1;
  long long clock_ = 0;
  std::map<int, std::shared_ptr<Recorded>> results_;
  std::map<int, std::shared_ptr<Session>> sessions_;
  SessionLimits limits_;
  mutable std::once_flag picture_once_;
  mutable std::optional<Result<std::string>> picture_;
  mutable std::once_flag doubts_once_;
  mutable std::vector<std::vector<std::string>> clip_doubts_;
  mutable std::once_flag mirror_of_once_;
  mutable std::vector<std::string> clip_mirror_of_;
};

}  // namespace mg::studio
