#include "motiongraph/core/json_text.h"
#include "motiongraph/export/positions_json.h"

#include <cmath>

#include <nlohmann/json.hpp>

#include "motiongraph/motion/forward_kinematics.h"

namespace mg {

nlohmann::json contacts_json(const Skeleton& skeleton, const PositionsJsonContacts& contacts, int frame_count) {
  using nlohmann::json;
  json names = json::array();
  json indices = json::array();
  const std::vector<ContactColumn> columns = contact_columns(contacts.feet);
  for (const ContactColumn& column : columns) {
    names.push_back(skeleton.joint(column.joint).name);
    indices.push_back(column.joint);
  }
  json planted = json::array();
  for (int f = 0; f < frame_count && f < static_cast<int>(contacts.masks.size()); ++f) {
    json row = json::array();
    for (const ContactColumn& column : columns) row.push_back((contacts.masks[f] & column.bit) != 0 ? 1 : 0);
    planted.push_back(std::move(row));
  }
  return {{"joints", std::move(names)}, {"joint_indices", std::move(indices)}, {"planted", std::move(planted)}};
}

std::string write_positions_json(const Skeleton& skeleton, const Motion& motion, const PositionsJsonContacts* contacts) {
  using nlohmann::json;
  json doc;
  doc["fps"] = motion.fps;
  json joints = json::array();
  for (const JointDef& joint : skeleton.joints()) {
    joints.push_back({{"name", joint.name}, {"parent", joint.parent}});
  }
  doc["joints"] = std::move(joints);
  const std::vector<Vec3> world = world_positions(skeleton, motion);
  // To the micrometre; a value whose micrometres overflow a double (past 1.8e302 m: a root at
  // 1e305, as a file may put it) is written as it is, where it was null.
  auto round_um = [](double v) { return std::abs(v) < 1e15 ? std::round(v * 1e6) / 1e6 + 0.0 : v; };
  json frames = json::array();
  const size_t count = static_cast<size_t>(skeleton.joint_count());
  for (int f = 0; f < motion.frame_count; ++f) {
    json frame = json::array();
    for (size_t j = 0; j < count; ++j) {
      const Vec3& p = world[f * count + j];
      frame.push_back(json::array({round_um(p.x()), round_um(p.y()), round_um(p.z())}));
    }
    frames.push_back(std::move(frame));
  }
  doc["positions"] = std::move(frames);
  if (contacts) doc["contacts"] = contacts_json(skeleton, *contacts, motion.frame_count);
  return json_text(doc) + "\n";
}

}  // namespace mg
