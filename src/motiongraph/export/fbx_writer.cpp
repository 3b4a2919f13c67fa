#include "motiongraph/export/fbx_writer.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <map>
#include <numbers>
#include <vector>

#include <fmt/format.h>
#include <Eigen/Geometry>

#include "motiongraph/core/json_text.h"
#include "motiongraph/core/unique_name.h"
#include "motiongraph/export/fbx_binary.h"
#include "motiongraph/export/keyed_joints.h"
#include "motiongraph/export/root_rotation_order.h"
#include "motiongraph/export/stick_figure.h"

namespace mg {

namespace {

using Affine = Eigen::Affine3d;

constexpr std::int64_t kTicksPerSecond = 46186158000;  // FBX's KTime unit
constexpr double kCentimetresPerMetre = 100.0;
constexpr double kDegreesPerRadian = 180.0 / std::numbers::pi;
constexpr std::int32_t kLinearKeys = 0x4;  // KeyAttrFlags: eInterpolationLinear

FbxRecord record(std::string name, std::vector<FbxValue> values = {}, std::vector<FbxRecord> records = {}) {
  return FbxRecord{std::move(name), std::move(values), std::move(records), false};
}

// A Properties70 entry: P: "name", "type", "label", "flags", values...
FbxRecord property(const char* name, const char* type, const char* label, const char* flags,
                   std::vector<FbxValue> values = {}) {
  std::vector<FbxValue> all{std::string(name), std::string(type), std::string(label), std::string(flags)};
  all.insert(all.end(), values.begin(), values.end());
  return record("P", std::move(all));
}
FbxRecord int_property(const char* name, std::int32_t value) { return property(name, "int", "Integer", "", {value}); }
FbxRecord enum_property(const char* name, std::int32_t value) { return property(name, "enum", "", "", {value}); }
FbxRecord time_property(const char* name, std::int64_t ticks) { return property(name, "KTime", "Time", "", {ticks}); }
FbxRecord vector_property(const char* name, const Vec3& v) {
  return property(name, name, "", "A", {v.x(), v.y(), v.z()});
}

// A name as FBX can hold it: valid UTF-8, without the bytes 0 and 1 that separate a name from its
// class ("name\0\1Class"), each of which becomes '_'.
std::string fbx_name(const std::string& name) {
  std::string out = valid_utf8(name);
  std::replace_if(
      out.begin(), out.end(), [](char c) { return c == '\0' || c == '\1'; }, '_');
  return out;
}

// An object's name as FBX stores it: "name\0\1Class" (`name` already an fbx_name).
std::string object_name(const std::string& name, const char* type) { return name + std::string("\0\1", 2) + type; }

// FBX's RotationOrder enum, named by the axis applied first: eEulerXYZ (0) is R = Rz Ry Rx.
std::int32_t rotation_order(const ComposeOrder& order) {
  static constexpr std::array<const char*, 6> kNames{"XYZ", "XZY", "YZX", "YXZ", "ZXY", "ZYX"};
  const std::string applied{axis_letter(order[2]), axis_letter(order[1]), axis_letter(order[0])};
  const auto it = std::find(kNames.begin(), kNames.end(), applied);
  assert(it != kNames.end());  // a Tait-Bryan order: the three axes once each (skeleton.h)
  return static_cast<std::int32_t>(it - kNames.begin());
}

// The rotation's angles (x, y, z, degrees) in the order, nearest to `near` (radians, per axis;
// none: the principal ones), which then becomes them, for the next frame's.
Vec3 euler_degrees(const ComposeOrder& order, const Quat& rotation, std::optional<Vec3>& near) {
  std::optional<Vec3> near_in_order;
  if (near)
    near_in_order = Vec3((*near)[static_cast<int>(order[0])], (*near)[static_cast<int>(order[1])],
                         (*near)[static_cast<int>(order[2])]);
  const Vec3 angles = decompose_euler(order, rotation, near_in_order);
  Vec3 xyz;
  for (int i = 0; i < 3; ++i) xyz[static_cast<int>(order[i])] = angles[i];
  near = xyz;
  return xyz * kDegreesPerRadian;
}

// FBX's TimeMode for a frame rate: its named rates, else custom (14) with CustomFrameRate.
std::int32_t time_mode(double fps) {
  static constexpr std::array<std::pair<double, std::int32_t>, 11> kModes{
      {{120, 1}, {100, 2}, {60, 3}, {50, 4}, {48, 5}, {30, 6}, {25, 10}, {24, 11}, {1000, 12}, {96, 15}, {72, 16}}};
  for (const auto& [rate, mode] : kModes) {
    if (fps == rate) return mode;
  }
  return 14;
}

// The time of a frame in ticks: exact when the rate divides FBX's tick rate (30, 24, 25, 60, 120...).
std::int64_t frame_ticks(int frame, double fps) {
  const auto whole = static_cast<std::int64_t>(fps);
  if (static_cast<double>(whole) == fps && whole > 0 && kTicksPerSecond % whole == 0)
    return frame * (kTicksPerSecond / whole);
  return std::llround(frame * static_cast<double>(kTicksPerSecond) / fps);
}

// Objects, their connections and their counts by type, as the file's Definitions lists them.
class Document {
 public:
  // A record of Objects, of one of the Definitions' types.
  FbxRecord& add(const char* type, FbxRecord object) {
    ++counts_[type];
    return objects_.add(std::move(object));
  }
  void connect(std::int64_t child, std::int64_t parent) {
    connections_.add(record("C", {std::string("OO"), child, parent}));
  }
  void connect_property(std::int64_t child, std::int64_t parent, const char* property_name) {
    connections_.add(record("C", {std::string("OP"), child, parent, std::string(property_name)}));
  }
  std::int64_t next_id() { return next_id_++; }

  // The file's records: header, global settings at `fps` for `stop_ticks`, the objects, their
  // connections, and `takes`.
  std::vector<FbxRecord> file(double fps, std::int64_t stop_ticks, const std::string& active_stack,
                              FbxRecord takes) && {
    std::vector<FbxRecord> out;
    out.push_back(record("FBXHeaderExtension", {},
                         {record("FBXHeaderVersion", {std::int32_t{1003}}),
                          record("FBXVersion", {static_cast<std::int32_t>(kFbxBinaryVersion)}),
                          record("EncryptionType", {std::int32_t{0}}),
                          // The creation time the file id goes with (fbx_binary.h).
                          record("CreationTimeStamp", {},
                                 {record("Version", {std::int32_t{1000}}), record("Year", {std::int32_t{1970}}),
                                  record("Month", {std::int32_t{1}}), record("Day", {std::int32_t{1}}),
                                  record("Hour", {std::int32_t{10}}), record("Minute", {std::int32_t{0}}),
                                  record("Second", {std::int32_t{0}}), record("Millisecond", {std::int32_t{0}})}),
                          record("Creator", {std::string("motiongraph")})}));
    out.push_back(record("FileId", {FbxRaw{std::string(kFbxFileId)}}));
    out.push_back(record("CreationTime", {std::string(kFbxCreationTime)}));
    out.push_back(record("Creator", {std::string("motiongraph")}));
    FbxRecord settings = record("Properties70");
    for (const auto& [name, value] : std::array<std::pair<const char*, std::int32_t>, 8>{{{"UpAxis", 1},
                                                                                          {"UpAxisSign", 1},
                                                                                          {"FrontAxis", 2},
                                                                                          {"FrontAxisSign", 1},
                                                                                          {"CoordAxis", 0},
                                                                                          {"CoordAxisSign", 1},
                                                                                          {"OriginalUpAxis", 1},
                                                                                          {"OriginalUpAxisSign", 1}}}) {
      settings.add(int_property(name, value));
    }
    settings.add(property("UnitScaleFactor", "double", "Number", "", {1.0}));
    settings.add(property("OriginalUnitScaleFactor", "double", "Number", "", {1.0}));
    settings.add(enum_property("TimeMode", time_mode(fps)));
    settings.add(time_property("TimeSpanStart", 0));
    settings.add(time_property("TimeSpanStop", stop_ticks));
    settings.add(property("CustomFrameRate", "double", "Number", "", {fps}));
    out.push_back(record("GlobalSettings", {}, {record("Version", {std::int32_t{1000}}), std::move(settings)}));
    out.push_back(record("Documents", {},
                         {record("Count", {std::int32_t{1}}),
                          record("Document", {next_id(), std::string("Scene"), std::string("Scene")},
                                 {record("Properties70", {},
                                         {property("SourceObject", "object", "", ""),
                                          property("ActiveAnimStackName", "KString", "", "", {active_stack})}),
                                  record("RootNode", {std::int64_t{0}})})}));
    FbxRecord references = record("References");
    references.block = true;
    out.push_back(std::move(references));
    counts_["GlobalSettings"] = 1;
    int total = 0;
    for (const auto& [type, n] : counts_) total += n;
    FbxRecord definitions =
        record("Definitions", {}, {record("Version", {std::int32_t{100}}), record("Count", {std::int32_t{total}})});
    for (const auto& [type, n] : counts_) {
      definitions.add(record("ObjectType", {type}, {record("Count", {std::int32_t{n}})}));
    }
    out.push_back(std::move(definitions));
    out.push_back(std::move(objects_));
    out.push_back(std::move(connections_));
    out.push_back(std::move(takes));
    return out;
  }

 private:
  FbxRecord objects_ = record("Objects");
  FbxRecord connections_ = record("Connections");
  std::map<std::string, int> counts_;
  std::int64_t next_id_ = 1000000;  // 0 is the scene's root
};

// The skeleton as LimbNode models: the static ancestors (a chain, root first), then one per joint,
// each with its node attribute. Their names as FBX holds them, unique (two names that differ only
// in bytes that are not UTF-8 would be one).
struct Models {
  std::vector<std::int64_t> ids;     // the ancestors', then the joints'
  std::vector<std::string> names;    // alike
  std::vector<Affine> rest;          // alike: world transforms at rest (metres; rest_transforms)
  std::vector<ComposeOrder> orders;  // the joints' rotation orders
  size_t first_joint = 0;            // the joints' place in the above

  std::int64_t joint(int j) const { return ids[first_joint + static_cast<size_t>(j)]; }
};

Models add_models(Document& doc, const Skeleton& skeleton, const Motion* first) {
  Models m;
  const auto add = [&](const std::string& wanted, const Vec3& translation_m, const Vec3& rotation_degrees,
                       const ComposeOrder& order, std::int64_t parent) {
    m.names.push_back(unique_name(fbx_name(wanted), [&](const std::string& n) {
      return std::find(m.names.begin(), m.names.end(), n) != m.names.end();
    }));
    const std::string& name = m.names.back();
    const std::int64_t attribute = doc.next_id(), model = doc.next_id();
    doc.add("NodeAttribute",
            record("NodeAttribute", {attribute, object_name(name, "NodeAttribute"), std::string("LimbNode")},
                   {record("TypeFlags", {std::string("Skeleton")})}));
    FbxRecord properties = record("Properties70");
    properties.add(vector_property("Lcl Translation", translation_m * kCentimetresPerMetre));
    properties.add(vector_property("Lcl Rotation", rotation_degrees));
    // The order counts only where rotation is active (the FBX SDK's rule).
    properties.add(property("RotationActive", "bool", "", "", {std::int32_t{1}}));
    properties.add(enum_property("RotationOrder", rotation_order(order)));
    properties.add(enum_property("InheritType", 1));
    properties.add(int_property("DefaultAttributeIndex", 0));
    doc.add("Model", record("Model", {model, object_name(name, "Model"), std::string("LimbNode")},
                            {record("Version", {std::int32_t{232}}), std::move(properties),
                             record("Culling", {std::string("CullingOff")})}));
    doc.connect(attribute, model);
    doc.connect(model, parent);
    m.ids.push_back(model);
  };
  for (const StaticAncestor& a : skeleton.static_ancestors()) {
    std::optional<Vec3> near;
    add(a.name, a.translation_m, euler_degrees(a.euler_order, a.rotation, near), a.euler_order,
        m.ids.empty() ? 0 : m.ids.back());
  }
  m.first_joint = m.ids.size();
  for (int j = 0; j < skeleton.joint_count(); ++j) {
    const JointDef& joint = skeleton.joint(j);
    m.orders.push_back(j == 0 ? root_rotation_order(skeleton) : joint.euler_order);
    const std::int64_t parent = j > 0 ? m.joint(joint.parent) : m.first_joint > 0 ? m.ids[m.first_joint - 1] : 0;
    add(joint.name, rest_node_translation(skeleton, first, j), Vec3::Zero(), m.orders.back(), parent);
  }
  m.rest = rest_transforms(skeleton, first);
  return m;
}

// A transform in centimetres as FBX stores a matrix: 16 numbers, column by column (the
// translation at 12..14).
std::vector<double> fbx_matrix(const Affine& metres) {
  Eigen::Matrix4d m = metres.matrix();
  m.block<3, 1>(0, 3) *= kCentimetresPerMetre;
  return std::vector<double>(m.data(), m.data() + 16);
}

// The stick figure skinned to the models at rest (stick_figure.h): a mesh at the origin with a grey
// material, its skin with a cluster for every model (Transform: its rest transform inverted;
// TransformLink: its rest transform; those no vertex hangs from too, for Unreal, which makes its
// skeleton of a skin's bones), and the bind pose of every model.
void add_stick_figure(Document& doc, const Skeleton& skeleton, const Models& models) {
  std::vector<Vec3> rest_world;
  for (int j = 0; j < skeleton.joint_count(); ++j)
    rest_world.push_back(models.rest[models.first_joint + static_cast<size_t>(j)].translation());
  const StickFigure figure = stick_figure(skeleton, rest_world);
  if (figure.empty()) return;
  std::vector<double> vertices, normals;
  std::vector<std::int32_t> polygons;
  for (size_t v = 0; v < figure.positions.size(); ++v) {
    for (int c = 0; c < 3; ++c) {
      vertices.push_back(figure.positions[v][c] * kCentimetresPerMetre);
      normals.push_back(figure.normals[v][c]);
    }
    // A triangle's last vertex index is written as -(index + 1).
    polygons.push_back(v % 3 == 2 ? -static_cast<std::int32_t>(v) - 1 : static_cast<std::int32_t>(v));
  }
  const std::int64_t geometry = doc.next_id(), mesh = doc.next_id(), material = doc.next_id(), skin = doc.next_id(),
                     pose = doc.next_id();
  const std::string mesh_name = unique_name("stick_figure", [&](const std::string& n) {
    return std::find(models.names.begin(), models.names.end(), n) != models.names.end();
  });
  const auto layer = [](const char* type, const char* mapping, const char* reference, const char* name, FbxValue data) {
    return record(type, {std::int32_t{0}},
                  {record("Version", {std::int32_t{101}}), record("Name", {std::string()}),
                   record("MappingInformationType", {std::string(mapping)}),
                   record("ReferenceInformationType", {std::string(reference)}), record(name, {std::move(data)})});
  };
  const auto layer_element = [](const char* type) {
    return record("LayerElement", {}, {record("Type", {std::string(type)}), record("TypedIndex", {std::int32_t{0}})});
  };
  doc.add("Geometry",
          record("Geometry", {geometry, object_name(mesh_name, "Geometry"), std::string("Mesh")},
                 {record("Vertices", {std::move(vertices)}), record("PolygonVertexIndex", {std::move(polygons)}),
                  record("GeometryVersion", {std::int32_t{124}}),
                  layer("LayerElementNormal", "ByPolygonVertex", "Direct", "Normals", std::move(normals)),
                  layer("LayerElementMaterial", "AllSame", "IndexToDirect", "Materials", std::vector<std::int32_t>{0}),
                  record("Layer", {std::int32_t{0}},
                         {record("Version", {std::int32_t{100}}), layer_element("LayerElementNormal"),
                          layer_element("LayerElementMaterial")})}));
  doc.add(
      "Model",
      record("Model", {mesh, object_name(mesh_name, "Model"), std::string("Mesh")},
             {record("Version", {std::int32_t{232}}),
              record("Properties70", {}, {enum_property("InheritType", 1), int_property("DefaultAttributeIndex", 0)}),
              record("Culling", {std::string("CullingOff")})}));
  doc.connect(geometry, mesh);
  doc.connect(mesh, 0);
  // Grey, as glTF's figure.
  doc.add("Material", record("Material", {material, object_name("bone", "Material"), std::string()},
                             {record("Version", {std::int32_t{102}}), record("ShadingModel", {std::string("phong")}),
                              record("MultiLayer", {std::int32_t{0}}),
                              record("Properties70", {},
                                     {property("DiffuseColor", "Color", "", "A", {0.8, 0.8, 0.8}),
                                      property("DiffuseFactor", "Number", "", "A", {1.0})})}));
  doc.connect(material, mesh);
  doc.add("Deformer", record("Deformer", {skin, object_name(mesh_name, "Deformer"), std::string("Skin")},
                             {record("Version", {std::int32_t{101}}), record("Link_DeformAcuracy", {50.0})}));
  doc.connect(skin, geometry);
  std::vector<std::vector<std::int32_t>> bound(models.ids.size());  // each model's vertices
  for (size_t v = 0; v < figure.joints.size(); ++v) {
    bound[models.first_joint + static_cast<size_t>(figure.joints[v])].push_back(static_cast<std::int32_t>(v));
  }
  for (size_t i = 0; i < models.ids.size(); ++i) {
    const std::int64_t cluster = doc.next_id();
    FbxRecord c = record("Deformer", {cluster, object_name(models.names[i], "SubDeformer"), std::string("Cluster")},
                         {record("Version", {std::int32_t{100}}), record("UserData", {std::string(), std::string()})});
    if (!bound[i].empty()) {  // a model no vertex hangs from has its cluster all the same: its bind matrix
      c.add(record("Indexes", {bound[i]}));
      c.add(record("Weights", {std::vector<double>(bound[i].size(), 1.0)}));
    }
    c.add(record("Transform", {fbx_matrix(models.rest[i].inverse())}));
    c.add(record("TransformLink", {fbx_matrix(models.rest[i])}));
    doc.add("Deformer", std::move(c));
    doc.connect(cluster, skin);
    doc.connect(models.ids[i], cluster);
  }
  FbxRecord bind_pose =
      record("Pose", {pose, object_name("BindPose", "Pose"), std::string("BindPose")},
             {record("Type", {std::string("BindPose")}), record("Version", {std::int32_t{100}}),
              record("NbPoseNodes", {static_cast<std::int32_t>(models.ids.size() + 1)}),
              record("PoseNode", {}, {record("Node", {mesh}), record("Matrix", {fbx_matrix(Affine::Identity())})})});
  for (size_t i = 0; i < models.ids.size(); ++i) {
    bind_pose.add(
        record("PoseNode", {}, {record("Node", {models.ids[i]}), record("Matrix", {fbx_matrix(models.rest[i])})}));
  }
  doc.add("Pose", std::move(bind_pose));
}

// An animation stack (with its one layer) named `name` playing the motion: per keyed joint a
// curve node of three curves, rotation in degrees (the joint's order, continuous) and translation
// in centimetres, a key per frame at the motion's own rate. Returns its last key's time.
std::int64_t add_stack(Document& doc, const Skeleton& skeleton, const Models& models, const KeyedJoints& keyed,
                       const std::string& name, const Motion& motion) {
  std::vector<std::int64_t> times;
  for (int f = 0; f < motion.frame_count; ++f) times.push_back(frame_ticks(f, motion.fps));
  const std::int64_t stop = times.back();
  const std::int64_t stack = doc.next_id(), layer = doc.next_id();
  doc.add("AnimationStack",
          record("AnimationStack", {stack, object_name(name, "AnimStack"), std::string()},
                 {record("Properties70", {},
                         {time_property("LocalStart", 0), time_property("LocalStop", stop),
                          time_property("ReferenceStart", 0), time_property("ReferenceStop", stop)})}));
  FbxRecord layer_record = record("AnimationLayer", {layer, object_name("BaseLayer", "AnimLayer"), std::string()});
  layer_record.block = true;
  doc.add("AnimationLayer", std::move(layer_record));
  doc.connect(layer, stack);
  // One curve node (T or R) of the joint's model: three curves of the frames' values.
  const auto curves = [&](int joint, const char* node_name, const char* channel,
                          const std::vector<std::array<float, 3>>& values) {
    const std::int64_t curve_node = doc.next_id();
    FbxRecord properties = record("Properties70");
    static constexpr std::array<const char*, 3> kAxes{"d|X", "d|Y", "d|Z"};
    for (int c = 0; c < 3; ++c)
      properties.add(property(kAxes[c], "Number", "", "A", {static_cast<double>(values[0][c])}));
    doc.add("AnimationCurveNode",
            record("AnimationCurveNode", {curve_node, object_name(node_name, "AnimCurveNode"), std::string()},
                   {std::move(properties)}));
    doc.connect(curve_node, layer);
    doc.connect_property(curve_node, models.joint(joint), channel);
    for (int c = 0; c < 3; ++c) {
      std::vector<float> keys;
      keys.reserve(values.size());
      for (const auto& v : values) keys.push_back(v[c]);
      const std::int64_t curve = doc.next_id();
      doc.add("AnimationCurve",
              record("AnimationCurve", {curve, object_name("", "AnimCurve"), std::string()},
                     {record("Default", {static_cast<double>(keys[0])}), record("KeyVer", {std::int32_t{4008}}),
                      record("KeyTime", {times}), record("KeyValueFloat", {std::move(keys)}),
                      // One attribute for every key: linear interpolation.
                      record("KeyAttrFlags", {std::vector<std::int32_t>{kLinearKeys}}),
                      record("KeyAttrDataFloat", {std::vector<float>{0.0f, 0.0f, 0.0f, 0.0f}}),
                      record("KeyAttrRefCount", {std::vector<std::int32_t>{motion.frame_count}})}));
      doc.connect_property(curve, curve_node, kAxes[c]);
    }
  };
  for (int j : keyed.turned) {
    std::vector<std::array<float, 3>> values;
    std::optional<Vec3> near;
    for (int f = 0; f < motion.frame_count; ++f) {
      Quat q = motion.rotations(f)[j];
      if (j == 0) q = below_static_ancestors(skeleton, q);
      const Vec3 degrees = euler_degrees(models.orders[static_cast<size_t>(j)], q, near);
      values.push_back(
          {static_cast<float>(degrees.x()), static_cast<float>(degrees.y()), static_cast<float>(degrees.z())});
    }
    curves(j, "R", "Lcl Rotation", values);
  }
  for (int j : keyed.moved) {
    const int slot = skeleton.translation_slot(j);
    std::vector<std::array<float, 3>> values;
    for (int f = 0; f < motion.frame_count; ++f) {
      const Vec3& t = motion.translations(f)[slot];
      const Vec3 cm = (j == 0 ? below_static_ancestors(skeleton, t) : t) * kCentimetresPerMetre;
      values.push_back({static_cast<float>(cm.x()), static_cast<float>(cm.y()), static_cast<float>(cm.z())});
    }
    curves(j, "T", "Lcl Translation", values);
  }
  return stop;
}

}  // namespace

Result<std::string> write_fbx(const Skeleton& skeleton, const Motion& motion, const std::string& animation_name,
                              const FbxWriteSettings& settings) {
  const FbxAnimation one{animation_name, &motion};
  return write_fbx(skeleton, std::span(&one, 1), settings);
}

Result<std::string> write_fbx(const Skeleton& skeleton, std::span<const FbxAnimation> animations,
                              const FbxWriteSettings& settings) {
  auto played = played_animations(skeleton, animations, "FBX");
  if (!played) return played.error();
  std::vector<const Motion*> motions;
  for (const ExportAnimation* a : *played) motions.push_back(a->motion);
  const Motion* first = motions.empty() ? nullptr : motions.front();
  Document doc;
  const Models models = add_models(doc, skeleton, first);
  if (settings.stick_figure) add_stick_figure(doc, skeleton, models);
  const KeyedJoints keyed = keyed_joints(skeleton, motions);
  std::vector<std::string> names;
  std::vector<FbxRecord> take_records;
  std::int64_t longest = 0;
  for (const ExportAnimation* a : *played) {
    names.push_back(unique_name(fbx_name(a->name), [&](const std::string& n) {
      return std::find(names.begin(), names.end(), n) != names.end();
    }));
    const std::int64_t stop = add_stack(doc, skeleton, models, keyed, names.back(), *a->motion);
    longest = std::max(longest, stop);
    take_records.push_back(
        record("Take", {names.back()},
               {record("FileName", {names.back() + ".tak"}), record("LocalTime", {std::int64_t{0}, stop}),
                record("ReferenceTime", {std::int64_t{0}, stop})}));
  }
  const std::string active = names.empty() ? std::string() : names.front();
  FbxRecord takes = record("Takes", {}, {record("Current", {active})});  // the first take
  for (FbxRecord& take : take_records) takes.add(std::move(take));
  // The file's rate: the first motion's (each stack's keys are at its own motion's).
  return encode_fbx_binary(std::move(doc).file(first ? first->fps : 30.0, longest, active, std::move(takes)));
}

}  // namespace mg
