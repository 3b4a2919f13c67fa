#include "motiongraph/evaluation/played_clips.h"

#include <algorithm>

namespace mg {

nlohmann::json played_clips_json(const MotionDatabase& db, std::span<const FrameSource> sources, double fps,
                                 int frames) {
  sources = sources.first(std::min(sources.size(), static_cast<size_t>(std::max(frames, 0))));
  nlohmann::json played = nlohmann::json::array();
  if (!(fps > 0.0)) fps = db.fps > 0.0 ? db.fps : 30.0;
  enum class Kind { kNone, kPiece, kBlend } kind = Kind::kNone;
  int clip = -1, last = -1;            // the open piece's clip and last frame (global)
  int blend_from = -1, blend_to = -1;  // the open blend's clips
  for (size_t i = 0; i < sources.size(); ++i) {
    const FrameSource& s = sources[i];
    const bool pure = s.departure == s.arrival || s.alpha >= 1.0 || s.alpha <= 0.0;
    const double at_s = static_cast<double>(i) / fps;
    if (pure) {
      const int frame = s.alpha <= 0.0 ? s.arrival : s.departure;
      const int of = db.clip_of(frame);
      if (kind == Kind::kPiece && of == clip && (frame == last + 1 || frame == last)) {
        nlohmann::json& piece = played.back();
        piece["seconds"] = piece["seconds"].get<double>() + 1.0 / fps;
        piece["last_frame"] = frame - db.clips[static_cast<size_t>(of)].first_frame;
        last = frame;
        continue;
      }
      played.push_back({{"at_s", at_s},
                        {"seconds", 1.0 / fps},
                        {"clip", db.clips[static_cast<size_t>(of)].name},
                        {"first_frame", frame - db.clips[static_cast<size_t>(of)].first_frame},
                        {"last_frame", frame - db.clips[static_cast<size_t>(of)].first_frame}});
      kind = Kind::kPiece;
      clip = of;
      last = frame;
      continue;
    }
    const int from = db.clip_of(s.departure), to = db.clip_of(s.arrival);
    if (kind == Kind::kBlend && from == blend_from && to == blend_to) {
      nlohmann::json& blend = played.back();
      blend["seconds"] = blend["seconds"].get<double>() + 1.0 / fps;
      continue;
    }
    played.push_back({{"at_s", at_s},
                      {"seconds", 1.0 / fps},
                      {"blend_from", db.clips[static_cast<size_t>(from)].name},
                      {"blend_to", db.clips[static_cast<size_t>(to)].name}});
    kind = Kind::kBlend;
    blend_from = from;
    blend_to = to;
  }
  return played;
}

}  // namespace mg
