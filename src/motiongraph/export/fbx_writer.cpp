#include "motiongraph/export/fbx_writer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <numbers>
#include <vector>

#include <Eigen/Geometry>
#include <fmt/format.h>

#include "motiongraph/core/json_text.h"
#include "motiongraph/core/unique_name.h"
#include "motiongraph/export/fbx_binary.h"
#include "motiongraph/export/keyed_joints.h"
#include "motiongraph/export/stick_figure.h"

namespace mg {

namespace {

using Affine = Eigen::Affine3d;

constexpr std::int64_t kTicksPerSecond = 46186158000;  // FBX's KTime unit
constexpr double kCentimetresPerMetre = 100.0;
constexpr double kDegreesPerRadian = 180.0 / std::numbers::pi;

// The FBX SDK checks the footer's id (fbx_binary.cpp) against the file id and the creation time:
// these three go together (every FBX writer without the SDK uses them).
constexpr unsigned char kFileId[16] = {0x28, 0xb3, 0x2a, 0xeb, 0xb6, 0x24, 0xcc, 0xc2,
                                       0xbf, 0xc8, 0xb0, 0x2a, 0xa9, 0x2b, 0xfc, 0xf1};
constexpr char kCreationTime[] = "1970-01-01 10:00:00:000";

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
FbxRecord int_property(const char* name, std::int32_t value) {
  return property(name, "int", "Integer", "", {value});
}
FbxRecord enum_property(const char* name, std::int32_t value) { return property(name, "enum", "", "", {value}); }
FbxRecord time_property(const char* name, std::int64_t ticks) { return property(name, "KTime", "Time", "", {ticks}); }
FbxRecord vector_property(const char* name, const Vec3& v) {
  return property(name, name, "", "A", {v.x(), v.y(), v.z()});
}

// A name as FBX can hold it: valid UTF-8, without the bytes 0 and 1 that separate a name from its
// class ("name\0\1Class"), each of which becomes '_'.
std::string fbx_name(const std::string& name) {
  std::string out = valid_utf8(name);
  std::replace_if(out.begin(), out.end(), [](char c) { return c == '\0' || c == '\1'; }, '_');
  return out;
}

// An object's name as FBX stores it: "name\0\1Class" (`name` already an fbx_name).
std::string object_name(const std::string& name, const char* type) { return name + std::string("\0\1", 2) + type; }

// The order joint 0's rotation is written in: the axis nearest the vertical (y, in the frame of
// the static ancestors above it) outermost, so that the middle angle, where Euler angles lock,
// is a lean rather than the heading a travelling figure turns through freely (CMU's root, in
// Acclaim's XYZ, has the heading in the middle: its keys jumped at every quarter turn).
ComposeOrder root_order(const Skeleton& skeleton) {
  const Vec3 up = skeleton.static_ancestor_rotation().conjugate() * Vec3::UnitY();
  int a = 0;
  up.cwiseAbs().maxCoeff(&a);
  return {static_cast<Axis>(a), static_cast<Axis>((a + 2) % 3), static_cast<Axis>((a + 1) % 3)};
}

// FBX's RotationOrder enum, named by the axis applied first: eEulerXYZ (0) is R = Rz Ry Rx.
std::int32_t rotation_order(const ComposeOrder& order) {
  static constexpr std::array<const char*, 6> kNames{"XYZ", "XZY", "YZX", "YXZ", "ZXY", "ZYX"};
  const std::string applied{axis_letter(order[2]), axis_letter(order[1]), axis_letter(order[0])};
  for (size_t i = 0; i < kNames.size(); ++i) {
    if (applied == kNames[i]) return static_cast<std::int32_t>(i);
  }
  return 0;
}

// The rotation's angles (x, y, z, degrees) in the order, nearest to `near` (radians, per axis).
Vec3 euler_degrees(const ComposeOrder& order, const Quat& rotation, std::optional<Vec3>& near) {
  std::optional<Vec3> near_in_order;
  if (near) near_in_order = Vec3((*near)[static_cast<int>(order[0])], (*near)[static_cast<int>(order[1])], (*near)[static_cast<int>(order[2])]);
  const Vec3 angles = decompose_euler(order, rotation, near_in_order);
  Vec3 xyz;
  for (int i = 0; i < 3; ++i) xyz[static_cast<int>(order[i])] = angles[i];
  near = xyz;
  return xyz * kDegreesPerRadian;
}

// FBX's TimeMode for a frame rate: its named rates, else custom (14) with CustomFrameRate.
std::int32_t time_mode(double fps) {
  static constexpr std::array<std::pair<double, std::int32_t>, 11> kModes{{{120, 1}, {100, 2}, {60, 3}, {50, 4}, {48, 5},
                                                                           {30, 6}, {25, 10}, {24, 11}, {1000, 12},
                                                                           {96, 15}, {72, 16}}};
  for (const auto& [rate, mode] : kModes) {
    if (fps == rate) return mode;
  }
  return 14;
}

// The time of a frame in ticks: exact when the rate divides FBX's tick rate (30, 24, 25, 60, 120...).
std::int64_t frame_ticks(int frame, double fps) {
  const auto whole = static_cast<std::int64_t>(fps);
  if (static_cast<double>(whole) == fps && whole > 0 && kTicksPerSecond % whole == 0) return frame * (kTicksPerSecond / whole);
  return std::llround(frame * static_cast<double>(kTicksPerSecond) / fps);
}

class Ids {
 public:
  std::int64_t next() { return next_++; }

 private:
  std::int64_t next_ = 1000000;  // 0 is the scene's root
};

}  // namespace

Result<std::string> write_fbx(const Skeleton& skeleton, const Motion& motion, const std::string& animation_name,
                              const FbxWriteSettings& settings) {
  const FbxAnimation one{animation_name, &motion};
  return write_fbx(skeleton, std::span(&one, 1), settings);
}

Result<std::string> write_fbx(const Skeleton& skeleton, std::span<const FbxAnimation> animations,
                              const FbxWriteSettings& settings) {
  std::vector<const FbxAnimation*> played;  // those with frames
  std::vector<const Motion*> motions;
  for (const FbxAnimation& a : animations) {
    if (a.name.empty()) return Error{"", 0, "an FBX animation needs a name"};
    if (!a.motion) return Error{"", 0, fmt::format("FBX animation '{}' has no motion", a.name)};
    if (auto s = check_fits(skeleton, *a.motion); !s) {
      return Error{"", 0, fmt::format("animation '{}': {}", a.name, s.error().message)};
    }
    if (a.motion->frame_count > 0) {
      played.push_back(&a);
      motions.push_back(a.motion);
    }
  }
  const Motion* first = motions.empty() ? nullptr : motions.front();
  Ids ids;
  FbxRecord objects = record("Objects");
  FbxRecord connections = record("Connections");
  const auto connect = [&](std::int64_t child, std::int64_t parent) {
    connections.add(record("C", {std::string("OO"), child, parent}));
  };
  const auto connect_property = [&](std::int64_t child, std::int64_t parent, const char* property_name) {
    connections.add(record("C", {std::string("OP"), child, parent, std::string(property_name)}));
  };

  // Models: the static ancestors (a chain, root first), then one per joint, each with its
  // LimbNode attribute. Their names as FBX holds them, unique (two names that differ only in bytes
  // that are not UTF-8 would be one), each its node attribute's too.
  std::vector<std::string> model_names;
  const auto model_name = [&](const std::string& wanted) {
    model_names.push_back(unique_name(fbx_name(wanted), [&](const std::string& n) {
      return std::find(model_names.begin(), model_names.end(), n) != model_names.end();
    }));
    return model_names.back();
  };
  const auto add_model = [&](const std::string& wanted, const Vec3& translation_m, const Vec3& rotation_degrees,
                             const ComposeOrder& order, std::int64_t parent) {
    const std::string name = model_name(wanted);
    const std::int64_t attribute = ids.next(), model = ids.next();
    objects.add(record("NodeAttribute", {attribute, object_name(name, "NodeAttribute"), std::string("LimbNode")},
                       {record("TypeFlags", {std::string("Skeleton")})}));
    FbxRecord properties = record("Properties70");
    properties.add(vector_property("Lcl Translation", translation_m * kCentimetresPerMetre));
    properties.add(vector_property("Lcl Rotation", rotation_degrees));
    // The order counts only where rotation is active (the FBX SDK's rule).
    properties.add(property("RotationActive", "bool", "", "", {std::int32_t{1}}));
    properties.add(enum_property("RotationOrder", rotation_order(order)));
    properties.add(enum_property("InheritType", 1));
    properties.add(int_property("DefaultAttributeIndex", 0));
    objects.add(record("Model", {model, object_name(name, "Model"), std::string("LimbNode")},
                       {record("Version", {std::int32_t{232}}), std::move(properties),
                        record("Culling", {std::string("CullingOff")})}));
    connect(attribute, model);
    connect(model, parent);
    return model;
  };
  std::int64_t parent = 0;
  std::vector<std::pair<std::int64_t, Affine>> bind_pose;  // each model's world transform at rest (metres)
  Affine above = Affine::Identity();
  for (const StaticAncestor& a : skeleton.static_ancestors()) {
    std::optional<Vec3> near;
    parent = add_model(a.name, a.translation_m, euler_degrees(a.euler_order, a.rotation, near), a.euler_order, parent);
    above = above * Eigen::Translation3d(a.translation_m) * a.rotation;
    bind_pose.emplace_back(parent, above);
  }
  const size_t first_joint = skeleton.static_ancestors().size();
  std::vector<std::int64_t> models;
  std::vector<ComposeOrder> orders;
  std::vector<Vec3> rest_world;
  for (int j = 0; j < skeleton.joint_count(); ++j) {
    const JointDef& joint = skeleton.joint(j);
    const Vec3 translation = rest_node_translation(skeleton, first, j);
    orders.push_back(j == 0 ? root_order(skeleton) : joint.euler_order);
    models.push_back(add_model(joint.name, translation, Vec3::Zero(), orders.back(), j == 0 ? parent : models[joint.parent]));
    // The pose's entries are the ancestors', then the joints' in order.
    const Affine parent_world = j == 0 ? above : bind_pose[first_joint + static_cast<size_t>(joint.parent)].second;
    bind_pose.emplace_back(models.back(), parent_world * Eigen::Translation3d(translation));
    rest_world.push_back(bind_pose.back().second.translation());
  }

  // The stick figure skinned to the joints at rest (stick_figure.h): a mesh, its skin with a
  // cluster per joint it binds (Transform: the joint's bind matrix inverted, the mesh standing at
  // the origin; TransformLink: the bind matrix), and the bind pose of every model.
  int figure_models = 0, geometries = 0, materials = 0, deformers = 0, poses = 0;
  const StickFigure figure = settings.stick_figure ? stick_figure(skeleton, rest_world) : StickFigure{};
  if (!figure.empty()) {
    const auto centimetres = [](const Affine& metres) {
      Eigen::Matrix4d m = metres.matrix();
      m.block<3, 1>(0, 3) *= kCentimetresPerMetre;
      return std::vector<double>(m.data(), m.data() + 16);  // column-major: the translation at 12..14
    };
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
    const std::int64_t geometry = ids.next(), mesh = ids.next(), material = ids.next(), skin = ids.next(), pose = ids.next();
    const std::string mesh_name = model_name("stick_figure");
    objects.add(record(
        "Geometry", {geometry, object_name(mesh_name, "Geometry"), std::string("Mesh")},
        {record("Vertices", {std::move(vertices)}), record("PolygonVertexIndex", {std::move(polygons)}),
         record("GeometryVersion", {std::int32_t{124}}),
         record("LayerElementNormal", {std::int32_t{0}},
                {record("Version", {std::int32_t{101}}), record("Name", {std::string()}),
                 record("MappingInformationType", {std::string("ByPolygonVertex")}),
                 record("ReferenceInformationType", {std::string("Direct")}), record("Normals", {std::move(normals)})}),
         record("LayerElementMaterial", {std::int32_t{0}},
                {record("Version", {std::int32_t{101}}), record("Name", {std::string()}),
                 record("MappingInformationType", {std::string("AllSame")}),
                 record("ReferenceInformationType", {std::string("IndexToDirect")}),
                 record("Materials", {std::vector<std::int32_t>{0}})}),
         record("Layer", {std::int32_t{0}},
                {record("Version", {std::int32_t{100}}),
                 record("LayerElement", {},
                        {record("Type", {std::string("LayerElementNormal")}), record("TypedIndex", {std::int32_t{0}})}),
                 record("LayerElement", {},
                        {record("Type", {std::string("LayerElementMaterial")}), record("TypedIndex", {std::int32_t{0}})})})}));
    objects.add(record("Model", {mesh, object_name(mesh_name, "Model"), std::string("Mesh")},
                       {record("Version", {std::int32_t{232}}),
                        record("Properties70", {}, {enum_property("InheritType", 1), int_property("DefaultAttributeIndex", 0)}),
                        record("Culling", {std::string("CullingOff")})}));
    connect(geometry, mesh);
    connect(mesh, 0);
    // Its material: grey, as glTF's figure.
    objects.add(record("Material", {material, object_name("bone", "Material"), std::string()},
                       {record("Version", {std::int32_t{102}}), record("ShadingModel", {std::string("phong")}),
                        record("MultiLayer", {std::int32_t{0}}),
                        record("Properties70", {}, {property("DiffuseColor", "Color", "", "A", {0.8, 0.8, 0.8}),
                                                    property("DiffuseFactor", "Number", "", "A", {1.0})})}));
    connect(material, mesh);
    objects.add(record("Deformer", {skin, object_name(mesh_name, "Deformer"), std::string("Skin")},
                       {record("Version", {std::int32_t{101}}), record("Link_DeformAcuracy", {50.0})}));
    connect(skin, geometry);
    std::map<int, std::vector<std::int32_t>> bound;  // joint -> its vertices
    for (int j = 0; j < skeleton.joint_count(); ++j) bound[j];  // every joint a bone of the skin (Unreal's skeleton)
    for (size_t v = 0; v < figure.joints.size(); ++v) bound[figure.joints[v]].push_back(static_cast<std::int32_t>(v));
    for (const auto& [joint, indexes] : bound) {
      const std::int64_t cluster = ids.next();
      const Affine& at_rest = bind_pose[first_joint + static_cast<size_t>(joint)].second;
      FbxRecord cluster_record = record("Deformer", {cluster, object_name(model_names[first_joint + static_cast<size_t>(joint)], "SubDeformer"), std::string("Cluster")},
                                        {record("Version", {std::int32_t{100}}), record("UserData", {std::string(), std::string()})});
      if (!indexes.empty()) {  // a joint no vertex hangs from has a cluster all the same: its bind matrix
        cluster_record.add(record("Indexes", {indexes}));
        cluster_record.add(record("Weights", {std::vector<double>(indexes.size(), 1.0)}));
      }
      cluster_record.add(record("Transform", {centimetres(at_rest.inverse())}));
      cluster_record.add(record("TransformLink", {centimetres(at_rest)}));
      objects.add(std::move(cluster_record));
      connect(cluster, skin);
      connect(models[static_cast<size_t>(joint)], cluster);
      deformers += 1;
    }
    FbxRecord pose_record = record("Pose", {pose, object_name("BindPose", "Pose"), std::string("BindPose")},
                                   {record("Type", {std::string("BindPose")}), record("Version", {std::int32_t{100}}),
                                    record("NbPoseNodes", {static_cast<std::int32_t>(bind_pose.size() + 1)}),
                                    record("PoseNode", {}, {record("Node", {mesh}), record("Matrix", {centimetres(Affine::Identity())})})});
    for (const auto& [model, world] : bind_pose) {
      pose_record.add(record("PoseNode", {}, {record("Node", {model}), record("Matrix", {centimetres(world)})}));
    }
    objects.add(std::move(pose_record));
    figure_models = 1;
    geometries = 1;
    materials = 1;
    deformers += 1;
    poses = 1;
  }

  // An animation stack (with its one layer) per motion: per keyed joint a curve node of three
  // curves, rotation in degrees and translation in centimetres.
  const KeyedJoints keyed = keyed_joints(skeleton, motions);
  std::vector<std::string> names;
  FbxRecord takes = record("Takes", {}, {record("Current", {std::string()})});
  std::int64_t longest = 0;
  int counts[4] = {0, 0, 0, 0};  // stacks, layers, curve nodes, curves
  for (const FbxAnimation* a : played) {
    const Motion& motion = *a->motion;
    const std::string name = unique_name(fbx_name(a->name), [&](const std::string& n) {
      return std::find(names.begin(), names.end(), n) != names.end();
    });
    names.push_back(name);
    std::vector<std::int64_t> times;
    for (int f = 0; f < motion.frame_count; ++f) times.push_back(frame_ticks(f, motion.fps));
    const std::int64_t stop = times.back();
    longest = std::max(longest, stop);
    const std::int64_t stack = ids.next(), layer = ids.next();
    objects.add(record("AnimationStack", {stack, object_name(name, "AnimStack"), std::string()},
                       {record("Properties70", {}, {time_property("LocalStart", 0), time_property("LocalStop", stop),
                                                    time_property("ReferenceStart", 0),
                                                    time_property("ReferenceStop", stop)})}));
    FbxRecord layer_record = record("AnimationLayer", {layer, object_name("BaseLayer", "AnimLayer"), std::string()});
    layer_record.block = true;
    objects.add(std::move(layer_record));
    connect(layer, stack);
    counts[0] += 1;
    counts[1] += 1;
    // One curve node (T or R) of the joint's model: three curves of the frames' values.
    const auto curves = [&](int joint, const char* node_name, const char* channel,
                            const std::vector<std::array<float, 3>>& values) {
      const std::int64_t curve_node = ids.next();
      FbxRecord properties = record("Properties70");
      static constexpr std::array<const char*, 3> kAxes{"d|X", "d|Y", "d|Z"};
      for (int c = 0; c < 3; ++c) properties.add(property(kAxes[c], "Number", "", "A", {static_cast<double>(values[0][c])}));
      objects.add(record("AnimationCurveNode", {curve_node, object_name(node_name, "AnimCurveNode"), std::string()},
                         {std::move(properties)}));
      connect(curve_node, layer);
      connect_property(curve_node, models[joint], channel);
      for (int c = 0; c < 3; ++c) {
        std::vector<float> keys;
        keys.reserve(values.size());
        for (const auto& v : values) keys.push_back(v[c]);
        const std::int64_t curve = ids.next();
        objects.add(record("AnimationCurve", {curve, object_name("", "AnimCurve"), std::string()},
                           {record("Default", {static_cast<double>(keys[0])}), record("KeyVer", {std::int32_t{4008}}),
                            record("KeyTime", {times}), record("KeyValueFloat", {std::move(keys)}),
                            // One attribute for every key: linear interpolation.
                            record("KeyAttrFlags", {std::vector<std::int32_t>{0x4}}),
                            record("KeyAttrDataFloat", {std::vector<float>{0.0f, 0.0f, 0.0f, 0.0f}}),
                            record("KeyAttrRefCount", {std::vector<std::int32_t>{motion.frame_count}})}));
        connect_property(curve, curve_node, kAxes[c]);
      }
      counts[2] += 1;
      counts[3] += 3;
    };
    for (int j : keyed.turned) {
      std::vector<std::array<float, 3>> values;
      std::optional<Vec3> near;
      for (int f = 0; f < motion.frame_count; ++f) {
        Quat q = motion.rotations(f)[j];
        if (j == 0) q = below_static_ancestors(skeleton, q);
        const Vec3 degrees = euler_degrees(orders[j], q, near);
        values.push_back({static_cast<float>(degrees.x()), static_cast<float>(degrees.y()), static_cast<float>(degrees.z())});
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
    takes.add(record("Take", {name}, {record("FileName", {name + ".tak"}), record("LocalTime", {std::int64_t{0}, stop}),
                                      record("ReferenceTime", {std::int64_t{0}, stop})}));
  }
  if (!names.empty()) takes.records.front().values.front() = names.front();

  // The document around them.
  const double fps = first ? first->fps : 30.0;
  std::vector<FbxRecord> file;
  file.push_back(record("FBXHeaderExtension", {},
                        {record("FBXHeaderVersion", {std::int32_t{1003}}),
                         record("FBXVersion", {static_cast<std::int32_t>(kFbxBinaryVersion)}),
                         record("EncryptionType", {std::int32_t{0}}),
                         record("CreationTimeStamp", {},
                                {record("Version", {std::int32_t{1000}}), record("Year", {std::int32_t{1970}}),
                                 record("Month", {std::int32_t{1}}), record("Day", {std::int32_t{1}}),
                                 record("Hour", {std::int32_t{10}}), record("Minute", {std::int32_t{0}}),
                                 record("Second", {std::int32_t{0}}), record("Millisecond", {std::int32_t{0}})}),
                         record("Creator", {std::string("motiongraph")})}));
  file.push_back(record("FileId", {FbxRaw{std::string(reinterpret_cast<const char*>(kFileId), sizeof kFileId)}}));
  file.push_back(record("CreationTime", {std::string(kCreationTime)}));
  file.push_back(record("Creator", {std::string("motiongraph")}));
  FbxRecord global_settings = record("Properties70");
  for (const auto& [name, value] : std::array<std::pair<const char*, std::int32_t>, 8>{
           {{"UpAxis", 1}, {"UpAxisSign", 1}, {"FrontAxis", 2}, {"FrontAxisSign", 1}, {"CoordAxis", 0},
            {"CoordAxisSign", 1}, {"OriginalUpAxis", 1}, {"OriginalUpAxisSign", 1}}}) {
    global_settings.add(int_property(name, value));
  }
  global_settings.add(property("UnitScaleFactor", "double", "Number", "", {1.0}));
  global_settings.add(property("OriginalUnitScaleFactor", "double", "Number", "", {1.0}));
  global_settings.add(enum_property("TimeMode", time_mode(fps)));
  global_settings.add(time_property("TimeSpanStart", 0));
  global_settings.add(time_property("TimeSpanStop", longest));
  global_settings.add(property("CustomFrameRate", "double", "Number", "", {fps}));
  file.push_back(record("GlobalSettings", {}, {record("Version", {std::int32_t{1000}}), std::move(global_settings)}));
  file.push_back(record(
      "Documents", {},
      {record("Count", {std::int32_t{1}}),
       record("Document", {ids.next(), std::string("Scene"), std::string("Scene")},
              {record("Properties70", {},
                      {property("SourceObject", "object", "", ""),
                       property("ActiveAnimStackName", "KString", "", "", {names.empty() ? std::string() : names.front()})}),
               record("RootNode", {std::int64_t{0}})})}));
  FbxRecord references = record("References");
  references.block = true;
  file.push_back(std::move(references));
  const int limb_count = static_cast<int>(models.size() + skeleton.static_ancestors().size());
  const std::array<std::pair<const char*, int>, 11> types{{{"GlobalSettings", 1},
                                                          {"NodeAttribute", limb_count},
                                                          {"Model", limb_count + figure_models},
                                                          {"Geometry", geometries},
                                                          {"Material", materials},
                                                          {"Deformer", deformers},
                                                          {"Pose", poses},
                                                          {"AnimationStack", counts[0]},
                                                          {"AnimationLayer", counts[1]},
                                                          {"AnimationCurveNode", counts[2]},
                                                          {"AnimationCurve", counts[3]}}};
  FbxRecord definitions = record("Definitions", {}, {record("Version", {std::int32_t{100}})});
  int total = 0;
  definitions.add(record("Count", {std::int32_t{0}}));  // set below
  for (const auto& [type, n] : types) {
    if (n == 0) continue;
    total += n;
    definitions.add(record("ObjectType", {std::string(type)}, {record("Count", {std::int32_t{n}})}));
  }
  definitions.records[1].values.front() = std::int32_t{total};
  file.push_back(std::move(definitions));
  file.push_back(std::move(objects));
  file.push_back(std::move(connections));
  file.push_back(std::move(takes));
  return encode_fbx_binary(file);
}

}  // namespace mg
