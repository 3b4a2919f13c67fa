// Acclaim Skeleton File (ASF) parser: text in memory -> AsfDocument, the file's content as
// written (file units, file angle units, names not yet resolved). Checks syntax and numbers;
// names, hierarchy and units are checked when the document is built into a skeleton
// (skeleton/asf_skeleton.h).
//
// Reads :units (mass, length, angle deg|rad), :root (order, axis, position, orientation),
// :bonedata (id, name, direction, length, axis with its order, dof in any subset and order,
// limits), :hierarchy (several children per line); skips :version, :name, :documentation and
// unknown sections and '#' comment lines; accepts LF or CRLF.
#pragma once

#include <array>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "motiongraph/core/error.h"
#include "motiongraph/skeleton/rotation.h"

namespace mg {

// Acclaim degrees of freedom. kLength ("l") is parsed but not supported by the builder.
enum class AcclaimDof { kRx, kRy, kRz, kTx, kTy, kTz, kLength };

const char* acclaim_dof_name(AcclaimDof dof);

struct AsfRoot {
  int line = 0;
  std::vector<AcclaimDof> order;            // the channels of the AMC root line, in order
  std::array<Axis, 3> axis_order{Axis::kX, Axis::kY, Axis::kZ};  // applied first to last
  Vec3 position = Vec3::Zero();             // file length units
  Vec3 orientation = Vec3::Zero();          // file angle units
};

struct AsfBone {
  int line = 0;                             // the line of its "begin"
  int id = 0;
  std::string name;
  Vec3 direction = Vec3::Zero();            // unit vector in the global (rest) frame
  double length = 0.0;                      // file length units
  Vec3 axis = Vec3::Zero();                 // file angle units
  std::array<Axis, 3> axis_order{Axis::kX, Axis::kY, Axis::kZ};  // applied first to last
  std::vector<AcclaimDof> dofs;             // in the order of the AMC values
  std::vector<std::pair<double, double>> limits;  // one per dof when given; may be infinite
  bool has_direction = false;
  bool has_length = false;
};

struct AsfHierarchyLine {
  int line = 0;
  std::string parent;
  std::vector<std::string> children;
};

struct AsfDocument {
  std::string file_name;
  double mass = 1.0;
  double length = 1.0;                      // ":units length 0.45": 1 file unit = 1/0.45 inch
  bool angles_in_degrees = true;
  bool has_root = false;
  AsfRoot root;
  std::vector<AsfBone> bones;
  std::vector<AsfHierarchyLine> hierarchy;
};

Result<AsfDocument> parse_asf(std::string_view text, std::string file_name);

}  // namespace mg
