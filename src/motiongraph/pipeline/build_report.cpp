// The build report's JSON.
#include "motiongraph/pipeline/build_report.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <fmt/format.h>

namespace mg {

using nlohmann::json;

json clips_json(const MotionDatabase& db, std::span<const ClipCoverage> coverage, const FrameFeatures* features) {
  json clips = json::array();
  for (size_t c = 0; c < db.clips.size(); ++c) {
    const DatabaseClip& clip = db.clips[c];
    json tags = json::array();
    for (size_t t = 0; t < db.tag_names.size(); ++t) {
      for (const TagRange& range : db.tag_ranges) {
        if (range.tag == static_cast<int>(t) && range.first_frame < clip.first_frame + clip.frame_count &&
            range.first_frame + range.frame_count > clip.first_frame) {
          tags.push_back(db.tag_names[t]);
          break;
        }
      }
    }
    clips.push_back(
        {{"name", clip.name},
         {"source", clip.source},
         {"first_frame", clip.first_frame},
         {"frames", clip.frame_count},
         {"tags", tags},
         {"skeleton", clip.skeleton < static_cast<int>(db.skeleton_names.size()) ? db.skeleton_names[clip.skeleton]
                                                                                 : std::to_string(clip.skeleton)}});
    if (c < coverage.size()) {
      const ClipCoverage& kept = coverage[c];
      clips.back()["kept_frames"] = kept.kept_frames;
      if (kept.kept_frames == 0 && features != nullptr) {
        clips.back()["best_join_rms_cm"] =
            kept.best_join < 0.0f ? json(nullptr) : json(rms_cm_of_distance(kept.best_join, *features));
      }
    }
  }
  return clips;
}

void add_clip_doubts(json& clips, const MotionDatabase& db, std::span<const DoubtedClip> doubts) {
  for (size_t c = 0; c < db.clips.size() && c < clips.size(); ++c) {
    clips[c]["doubts"] = json::array();
    for (const DoubtedClip& d : doubts) {
      if (d.name == db.clips[c].name) clips[c]["doubts"] = d.doubts.phrases();
    }
  }
}

void add_mirror_of(json& clips, const MotionDatabase& db, const DatabaseLoadNotes& notes) {
  // The mirrored clips are the last ones, in the order of notes.mirrored (mirror_clips).
  const size_t first_mirrored = db.clips.size() - std::min(notes.mirrored.size(), db.clips.size());
  for (size_t c = 0; c < db.clips.size() && c < clips.size(); ++c) {
    clips[c]["mirror_of"] = c < first_mirrored ? json(nullptr) : json(notes.mirror_sources[c - first_mirrored]);
  }
}

json turning_json(const TurningBalance& turning) {
  return {{"travel_s", turning.travel_s},
          {"left_deg", turning.left_deg},
          {"right_deg", turning.right_deg},
          {"lopsided", turning.lopsided()}};
}

json unmirrored_json(const DatabaseLoadNotes& notes) {
  json unmirrored = json::array();
  for (const auto& u : notes.unmirrored) {
    unmirrored.push_back({{"skeleton", u.skeleton}, {"reason", u.reason}, {"clips", u.clips}});
  }
  return unmirrored;
}

void add_mirroring(json& report, const MotionDatabase& db, const DatabaseLoadNotes& notes) {
  add_mirror_of(report["clips"], db, notes);
  report["mirroring"] = {{"mode", mirroring_name(notes.mirroring)},
                         {"turning", turning_json(notes.turning)},
                         {"mirrored", notes.mirrored.size()},
                         {"unmirrored", unmirrored_json(notes)}};
}

json coverage_point_json(const CoveragePoint& p, const MotionDatabase& db, const std::vector<int>& tags) {
  json per_tag = json::object();
  for (size_t i = 0; i < tags.size() && i < p.tag_coverage.size(); ++i)
    per_tag[motion_class_name(db, tags[i])] = p.tag_coverage[i];
  json out = {{"threshold", p.threshold},     {"rms_cm", p.rms_cm},
              {"quantile", p.quantile},       {"graph", p.graph},
              {"coverage", p.coverage},       {"tag_coverage", per_tag},
              {"kept_frames", p.kept_frames}, {"transitions", p.transitions}};
  if (!p.tag_thresholds.empty()) {
    json own = json::object(), own_rms = json::object();
    for (size_t i = 0; i < tags.size() && i < p.tag_thresholds.size(); ++i) {
      own[motion_class_name(db, tags[i])] = p.tag_thresholds[i];
      own_rms[motion_class_name(db, tags[i])] = p.tag_rms_cm[i];
    }
    out["tag_thresholds"] = own;
    out["tag_rms_cm"] = own_rms;
  }
  return out;
}

json threshold_choice_json(const ThresholdChoice& choice, const MotionDatabase& db,
                           const ThresholdChoiceSettings& settings) {
  json curve = json::array();
  for (const CoveragePoint& p : choice.curve) curve.push_back(coverage_point_json(p, db, choice.tags));
  std::vector<std::string> names;
  json targets = json::object();
  for (size_t i = 0; i < choice.tags.size(); ++i) {
    names.push_back(motion_class_name(db, choice.tags[i]));
    targets[names.back()] = choice.targets[i];
  }
  if (choice.tags.empty() && !choice.targets.empty()) targets["all"] = choice.targets[0];
  json own = json::object();  // per type: the thresholds chosen (D)
  for (size_t i = 0; i < choice.tag_thresholds.size() && i < names.size(); ++i) {
    own[names[i]] = choice.tag_thresholds[i];
  }
  json out = settings;
  out.update({{"target_rate", choice.target_rate},
              {"targets", targets},
              {"reached", choice.reached},
              {"untagged_holds", choice.untagged_holds},
              {"threshold", choice.threshold},
              {"rms_cm", choice.rms_cm},
              {"per_type", !choice.tag_thresholds.empty()},
              {"tag_thresholds", own},
              {"motion_types", names},
              {"curve", curve}});
  return out;
}

json path_check_json(const PathCheck& check, const PathCheckSettings& settings) {
  const auto finite_or_null = [](double v) { return std::isfinite(v) ? json(v) : json(nullptr); };
  const auto point_json = [&](const PathCheckPoint& p) {
    return json{{"threshold", p.threshold},
                {"rms_cm", p.rms_cm},
                {"graph", p.graph},
                {"mean_deviation_m", p.mean_deviation_m},
                {"max_deviation_m", p.max_deviation_m},
                {"reached_end", p.reached_end},
                {"arc_covered_m", p.arc_covered_m},
                {"transitions", p.transitions},
                {"seconds", p.seconds},
                {"probe_deviations_m", json::array({finite_or_null(p.probe_deviations_m[0]),
                                                    finite_or_null(p.probe_deviations_m[1])})}};
  };
  json points = json::array();
  for (const PathCheckPoint& p : check.points) points.push_back(point_json(p));
  json out = settings;
  out.update({{"probe_length_m", check.probe_length_m},
              {"skipped", check.skipped},
              {"travel_share", check.travel_share},
              {"passed", check.passed},
              {"threshold", check.threshold},
              {"rms_cm", check.rms_cm},
              {"points", points},
              {"delivered", check.delivered ? point_json(*check.delivered) : json(nullptr)}});
  return out;
}

json unjoined_json(const std::vector<UnjoinedPair>& pairs, const MotionDatabase& db, const FrameFeatures& features,
                   const GraphStatistics* after) {
  auto kept = [&](int tag) {
    if (after == nullptr) return false;
    return std::any_of(after->tags.begin(), after->tags.end(),
                       [&](const TagStatistics& s) { return s.tag == tag && s.frames > 0; });
  };
  json out = json::array();
  for (const UnjoinedPair& p : pairs) {
    const bool has_best = p.best_distance >= 0.0f;
    const double rms = has_best ? rms_cm_of_distance(p.best_distance, features) : 0.0;
    std::string why;
    switch (p.reason) {
      case UnjoinedReason::kNoCore:
        why = "one of them forms no loop of its own transitions";
        break;
      case UnjoinedReason::kNoCandidate:
        why = "no candidate transition leads from the one to the other";
        break;
      case UnjoinedReason::kAboveCap:
        why = fmt::format("the best candidate, RMS {:.2f} cm, is above the bridge cap", rms);
        break;
    }
    out.push_back({{"from", db.tag_names[p.from_tag]},
                   {"to", db.tag_names[p.to_tag]},
                   {"why", why},
                   {"best_distance", has_best ? json(p.best_distance) : json(nullptr)},
                   {"best_rms_cm", has_best ? json(rms) : json(nullptr)},
                   {"through_graph", kept(p.from_tag) && kept(p.to_tag)}});
  }
  return out;
}

json foot_contacts_json(const MotionDatabase& db) {
  if (db.frame_contacts.empty()) return {{"error", db.contacts_error.empty() ? "not found" : db.contacts_error}};
  json skeletons = json::array();
  for (size_t s = 0; s < db.skeletons.size(); ++s) {
    auto feet = find_foot_joints(db.skeletons[s], db.foot_names);
    if (!feet) continue;
    const auto name = [&](int joint) { return joint < 0 ? json(nullptr) : json(db.skeletons[s].joint(joint).name); };
    skeletons.push_back({{"skeleton", s < db.skeleton_names.size() ? db.skeleton_names[s] : std::to_string(s)},
                         {"left_ankle", name(feet->left.ankle)},
                         {"left_toe", name(feet->left.toe)},
                         {"right_ankle", name(feet->right.ankle)},
                         {"right_toe", name(feet->right.toe)}});
  }
  json planted = json::object();
  const std::pair<const char*, ContactMask> bits[] = {{"left_ankle", contact_bit(FootSide::kLeft, FootPart::kAnkle)},
                                                      {"left_toe", contact_bit(FootSide::kLeft, FootPart::kToe)},
                                                      {"right_ankle", contact_bit(FootSide::kRight, FootPart::kAnkle)},
                                                      {"right_toe", contact_bit(FootSide::kRight, FootPart::kToe)}};
  for (const auto& [key, bit] : bits) {
    long long count = 0;
    for (const ContactMask m : db.frame_contacts) count += (m & bit) != 0 ? 1 : 0;
    planted[key] = static_cast<double>(count) / static_cast<double>(db.frame_contacts.size());
  }
  return {{"feet", skeletons}, {"planted_share", planted}};
}

json build_report(const BuildReportParts& parts) {
  const MotionDatabase& db = parts.db;
  const FrameFeatures& features = parts.features;
  const TransitionSelection& selection = parts.selected.selection;
  const PrunedGraph* pruned = parts.pruned;
  json tag_thresholds = json::array();
  for (const TagThreshold& t : selection.tag_thresholds) {
    tag_thresholds.push_back({{"tag", motion_class_name(db, t.tag)},
                              {"candidates", t.candidates},
                              {"threshold", t.threshold},
                              {"rms_cm", rms_cm_of_distance(t.threshold, features)},
                              {"chosen", t.given}});
  }
  json bridges = json::array();
  for (size_t b = 0; b < parts.selected.bridges.size(); ++b) {
    const Transition& t = parts.selected.bridges[b];
    bridges.push_back({{"from_frame", t.from_frame},
                       {"to_frame", t.to_frame},
                       {"distance", t.distance},
                       {"rms_cm", rms_cm_of_distance(t.distance, features)},
                       {"blend_frames", parts.selected.bridge_blends[b]}});
  }
  std::vector<double> point_weights(parts.layout.weight.begin(), parts.layout.weight.end());
  return {
      {"frames", db.frame_count()},
      {"fps", db.fps},
      {"window", features.window},
      {"points", parts.layout.point_count()},
      {"point_weights", point_weights},
      {"window_weights", features.taper},
      {"window_weight", features.window_weight},
      {"clips", clips_json(db, parts.coverage, &features)},
      {"foot_contacts", foot_contacts_json(db)},
      {"tags", db.tag_names},
      {"distance_settings", parts.distance_settings},
      {"threshold_mode", parts.threshold_mode},
      {"threshold", selection.threshold},
      {"threshold_rms_cm", rms_cm_of_distance(selection.threshold, features)},
      {"threshold_quantile", selection.threshold_quantile},
      {"threshold_choice", parts.threshold_choice},
      {"path_check", parts.path_check},
      {"locality_radius", selection.locality_radius},
      {"spacing", parts.spacing.resolved(features.window)},
      {"bridge_settings", parts.bridge_settings},
      {"tag_thresholds", tag_thresholds},
      {"counts",
       {{"pairs", static_cast<long long>(features.frames) * features.frames},
        {"finite_pairs", parts.candidates.histogram.total()},
        {"local_minima", parts.candidates.minima.size()},
        {"below_threshold", selection.candidates_below_threshold},
        {"transitions", selection.transitions.size()},
        {"survived_first_pruning", pruned ? pruned->survived_first_pruning : 0},
        {"spaced", pruned ? pruned->prune.before.transitions : 0},
        {"bridges", parts.selected.bridges.size()},
        {"transitions_kept", pruned ? pruned->prune.after.transitions : 0},
        {"bridge_blends_placed", pruned ? pruned->bridge_blends_placed : true}}},
      {"graph_before", pruned ? json::parse(to_json(pruned->prune.before, db.tag_names)) : json(nullptr)},
      {"graph_after", pruned ? json::parse(to_json(pruned->prune.after, db.tag_names)) : json(nullptr)},
      {"bridges", bridges},
      {"unjoined", unjoined_json(parts.selected.unjoined, db, features, pruned ? &pruned->prune.after : nullptr)},
      {"distance_cache", parts.distance_cache},
      {"processes", parts.processes},
      {"peak_memory_mb", parts.peak_memory_mb},
      {"share_seconds", parts.share_seconds},
      {"restored_tiles", parts.restored_tiles},
  };
}

}  // namespace mg
