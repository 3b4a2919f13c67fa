// The studio's JSON API as a function from a request (method, path, query, body) to a
// response (status, content type, body), so it is tested without sockets; http_server.h
// puts it on the network. Errors are 4xx with {"error": "one line"}; every number is
// checked (type, finite, range) and every answer is bounded in size. A body or query key a
// request does not take is refused, as is a query key given twice; a path index is plain decimal
// digits (no sign, no leading zero). HEAD is answered as GET; OPTIONS says (Allow) which methods
// a path takes, and a method it does not take is 405 saying the same.
//
//   GET  /api/summary                       the graph, database and per-tag statistics
//   GET  /api/clips                         the clips
//   GET  /api/clips/{i}/frames?from=&count= world joint positions of clip frames (count <= 600)
//   GET  /api/matrix.png                    the distance picture (block minima)
//   GET  /api/transitions                   the graph's transitions
//   GET  /api/transitions/{i}/poses         the two windows a transition joins, root-centred
//   POST /api/walk                          {"from", "to", "min_frames", "cost", "seed", "cleanup"}
//   POST /api/path                          {"points": [[x, z], ...], "segments": [...], "cleanup"}
//   POST /api/steer/sessions                {"heading_deg", "tag", "cleanup"}
// "cleanup" (default true): the foot clean-up (synthesis/foot_cleanup.h); walk and path
// answers say whether it ran ("cleanup") and measure the result against its source clips
// ("foot_slide", evaluation/foot_slide_report.h).
//   POST /api/steer/sessions/{id}/step      {"heading_deg", "tag", "min_frames"}
//   GET  /api/results/{id}.bvh              a synthesized motion as BVH (metres)
//   GET  /api/results/{id}.glb              the same as binary glTF 2.0 (metres; export/gltf_writer.h)
//   GET  /api/results/{id}.gltf             the same as glTF JSON, its buffer embedded (base64)
//   GET  /api/results/{id}.fbx              the same as binary FBX 7.4 (centimetres; export/fbx_writer.h)
//        ?root_motion=1 (any)               with a root-motion joint above the root (motion/root_motion.h)
//        ?figure=0 (.glb, .gltf, .fbx)      without the stick figure (the skeleton and its animation)
// Every answer with frames to play (clip frames, both windows of a transition, walk, path,
// steering step) carries their foot contacts as the CLI writes them (export/positions_json.h):
// "contacts": {"joints": [foot joint names], "joint_indices": [...], "planted": [frame][joint]
// 0 or 1}, the contacts each frame carries from its database frame (the ones the clean-up
// holds); null when the graph's feet were not found.
#pragma once

#include <map>
#include <string>

#include "studio/synthesis_service.h"

namespace mg::studio {

struct ApiRequest {
  std::string method;  // "GET", "HEAD" (answered as GET), "POST", "OPTIONS", ...
  std::string path;    // "/api/..." without the query
  std::multimap<std::string, std::string> query;  // a key given twice is refused
  std::string body;
};

struct ApiResponse {
  int status = 200;
  std::string content_type = "application/json";
  std::string body;
  std::string file_name;  // when set, the body is a download of that name
  std::string allow;      // the methods the path takes ("GET, HEAD"): OPTIONS answers and 405s carry it
};

class StudioApi {
 public:
  static constexpr int kMaxFramesPerRequest = 600;
  static constexpr double kMaxPathLengthM = 200.0;
  static constexpr double kMaxPathCoordinateM = 10000.0;  // a point's x and z, either way
  static constexpr int kMaxPathPoints = 5000;
  static constexpr int kMaxPathSegments = 100;

  explicit StudioApi(SynthesisService& service) : service_(&service) {}

  // Never throws; anything unexpected is a 500 with a message.
  ApiResponse handle(const ApiRequest& request) const;

 private:
  ApiResponse route(const ApiRequest& request) const;
  SynthesisService* service_;
};

}  // namespace mg::studio
