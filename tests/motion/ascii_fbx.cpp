#include "motion/ascii_fbx.h"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include <fmt/format.h>

#include "motiongraph/skeleton/rotation.h"

namespace mg::test {

namespace {

constexpr double kDegrees = 180.0 / std::numbers::pi;
constexpr long long kTicksPerSecond = 46'186'158'000LL;  // FBX's KTime

// FBX's rotation orders by their enum (eEulerXYZ = 0 .. eEulerZYX = 5): axes in the order they
// apply, so that XYZ is R = Rz * Ry * Rx.
constexpr const char* kOrders[6] = {"XYZ", "XZY", "YZX", "YXZ", "ZXY", "ZYX"};

ComposeOrder compose_order(int fbx_order) {
  const auto applied = parse_axis_string(kOrders[fbx_order]);
  return {(*applied)[2], (*applied)[1], (*applied)[0]};
}

// Degrees about x, y and z (FBX's d|X, d|Y, d|Z) for `rotation` in FBX's order.
Vec3 euler_degrees(int fbx_order, const Quat& rotation) {
  const ComposeOrder order = compose_order(fbx_order);
  const Vec3 angles = decompose_euler(order, rotation);
  Vec3 out;
  for (int i = 0; i < 3; ++i) out[static_cast<int>(order[static_cast<size_t>(i)])] = angles[i] * kDegrees;
  return out;
}

Quat from_degrees(int fbx_order, const Vec3& degrees) {
  const ComposeOrder order = compose_order(fbx_order);
  Vec3 angles;
  for (int i = 0; i < 3; ++i) angles[i] = degrees[static_cast<int>(order[static_cast<size_t>(i)])] / kDegrees;
  return compose_euler(order, angles);
}

std::string vec(const Vec3& v) { return fmt::format("{:.9g},{:.9g},{:.9g}", v.x(), v.y(), v.z()); }

std::string array(const std::string& name, const std::vector<std::string>& values) {
  std::string joined;
  for (const std::string& v : values) joined += (joined.empty() ? "" : ",") + v;
  return fmt::format("\t\t{}: *{} {{\n\t\t\ta: {}\n\t\t}}\n", name, values.size(), joined);
}

}  // namespace

std::string ascii_fbx(const std::vector<std::pair<std::string, Clip>>& clips, const AsciiFbxSettings& settings) {
  if (clips.empty()) throw std::invalid_argument("ascii_fbx: no clip");
  const Skeleton& skeleton = clips.front().second.skeleton;
  const int joints = skeleton.joint_count();
  const double fps = clips.front().second.motion.fps;
  for (int j = 1; j < joints; ++j) {
    if (skeleton.translation_slot(j) >= 0) throw std::invalid_argument("ascii_fbx: a joint other than the root moves");
  }
  // Each joint's frame in the file: our frame turned by its own rotation; its PreRotation and
  // rotation order, all different.
  std::vector<Quat> frame(static_cast<size_t>(joints)), pre(static_cast<size_t>(joints));
  std::vector<Vec3> pre_degrees(static_cast<size_t>(joints));
  std::vector<int> order(static_cast<size_t>(joints));
  for (int j = 0; j < joints; ++j) {
    const size_t js = static_cast<size_t>(j);
    frame[js] = Quat(Eigen::AngleAxisd(0.3 + 0.7 * j, Vec3(1.0, 0.5 * j, -0.25 * (j % 3)).normalized()));
    pre_degrees[js] = Vec3(15.0 * (j % 7) - 40.0, 90.0 - 11.0 * (j % 5), 25.0 * (j % 4));
    pre[js] = from_degrees(0, pre_degrees[js]);  // FBX's pre-rotations are XYZ whatever the order
    order[js] = j % 6;
  }
  // Our world -> the file's world: our +y turned to its up axis, in its unit.
  if (settings.up.size() != 2 || (settings.up[0] != '+' && settings.up[0] != '-') ||
      std::string_view("xyz").find(settings.up[1]) == std::string_view::npos) {
    throw std::invalid_argument("ascii_fbx: up is +x, -z, ...");
  }
  const int up_axis = settings.up[1] == 'x' ? 0 : settings.up[1] == 'y' ? 1 : 2;
  Vec3 up = Vec3::Zero();
  up[up_axis] = settings.up[0] == '-' ? -1.0 : 1.0;
  const Quat to_file = up.y() < -0.5 ? Quat(Eigen::AngleAxisd(std::numbers::pi, Vec3::UnitX()))
                                     : Quat::FromTwoVectors(Vec3::UnitY(), up);
  const double units_per_metre = 100.0 / settings.unit_scale_factor;
  // Armature space: under the armature's rotation and scale.
  const Quat armature_inverse = settings.armature_rotation.conjugate();
  const double length = units_per_metre / settings.armature_scale;  // armature units per metre of ours

  // Per joint per frame: the translation (in its parent's file frame) and Euler degrees of its Lcl Rotation.
  struct Keys {
    std::vector<Vec3> translation;  // root only
    std::vector<std::vector<Vec3>> degrees;  // [joint][frame]
  };
  const auto keys_of = [&](const Clip& clip) {
    Keys keys;
    keys.degrees.assign(static_cast<size_t>(joints), {});
    for (int f = 0; f < clip.motion.frame_count; ++f) {
      const auto rotations = clip.motion.rotations(f);
      for (int j = 0; j < joints; ++j) {
        const size_t js = static_cast<size_t>(j);
        // The file's world rotation of the joint: ours (taken to the armature's space), turned by its frame.
        // Parent: W_p = armature^-1 * to_file * Ours_p * frame_p, so Lcl = pre^-1 * W_p^-1 * W_j.
        Quat local;
        if (j == 0) {
          local = pre[js].conjugate() * armature_inverse * to_file * rotations[0] * frame[0];
        } else {
          const size_t p = static_cast<size_t>(skeleton.parent(j));
          local = pre[js].conjugate() * frame[p].conjugate() * rotations[js] * frame[js];
        }
        keys.degrees[js].push_back(euler_degrees(order[js], local.normalized()));
      }
      keys.translation.push_back(length * (armature_inverse * (to_file * clip.motion.translations(f)[0])));
    }
    return keys;
  };

  std::string objects, connections;
  long long next_id = 1000;
  const long long armature = next_id++;
  objects += fmt::format(
      "\tModel: {}, \"Model::Armature\", \"Null\" {{\n\t\tVersion: 232\n\t\tProperties70:  {{\n"
      "\t\t\tP: \"Lcl Rotation\", \"Lcl Rotation\", \"\", \"A\",{}\n"
      "\t\t\tP: \"Lcl Scaling\", \"Lcl Scaling\", \"\", \"A\",{}\n\t\t}}\n\t}}\n",
      armature, vec(euler_degrees(0, settings.armature_rotation)), vec(Vec3::Constant(settings.armature_scale)));
  connections += fmt::format("\tC: \"OO\",{},0\n", armature);
  const Keys first = keys_of(clips.front().second);
  std::vector<long long> model(static_cast<size_t>(joints));
  for (int j = 0; j < joints; ++j) {
    const size_t js = static_cast<size_t>(j);
    model[js] = next_id++;
    const Vec3 translation =
        j == 0 ? first.translation[0]
               : Vec3(length * (frame[static_cast<size_t>(skeleton.parent(j))].conjugate() * skeleton.joint(j).rest_offset_m));
    objects += fmt::format(
        "\tModel: {}, \"Model::{}\", \"LimbNode\" {{\n\t\tVersion: 232\n\t\tProperties70:  {{\n"
        "\t\t\tP: \"RotationActive\", \"bool\", \"\", \"\",1\n"
        "\t\t\tP: \"RotationOrder\", \"enum\", \"\", \"\",{}\n"
        "\t\t\tP: \"PreRotation\", \"Vector3D\", \"Vector\", \"\",{}\n"
        "\t\t\tP: \"Lcl Translation\", \"Lcl Translation\", \"\", \"A\",{}\n"
        "\t\t\tP: \"Lcl Rotation\", \"Lcl Rotation\", \"\", \"A\",{}\n\t\t}}\n\t}}\n",
        model[js], skeleton.joint(j).name, order[js], vec(pre_degrees[js]), vec(translation), vec(first.degrees[js][0]));
    connections += fmt::format("\tC: \"OO\",{},{}\n", model[js],
                               j == 0 ? armature : model[static_cast<size_t>(skeleton.parent(j))]);
  }
  // An animation curve node of three curves (d|X, d|Y, d|Z) on a model's property.
  const auto curves = [&](long long layer, long long target, const char* property, const char* node_name,
                          const std::vector<Vec3>& values, double rate) {
    const long long node = next_id++;
    objects += fmt::format(
        "\tAnimationCurveNode: {}, \"AnimCurveNode::{}\", \"\" {{\n\t\tProperties70:  {{\n"
        "\t\t\tP: \"d|X\", \"Number\", \"\", \"A\",{:.9g}\n\t\t\tP: \"d|Y\", \"Number\", \"\", \"A\",{:.9g}\n"
        "\t\t\tP: \"d|Z\", \"Number\", \"\", \"A\",{:.9g}\n\t\t}}\n\t}}\n",
        node, node_name, values[0].x(), values[0].y(), values[0].z());
    connections += fmt::format("\tC: \"OO\",{},{}\n\tC: \"OP\",{},{}, \"{}\"\n", node, layer, node, target, property);
    std::vector<std::string> times;
    for (size_t k = 0; k < values.size(); ++k) {
      times.push_back(fmt::format("{}", std::llround(static_cast<double>(k) * static_cast<double>(kTicksPerSecond) / rate)));
    }
    for (int axis = 0; axis < 3; ++axis) {
      const long long curve = next_id++;
      std::vector<std::string> v;
      for (const Vec3& value : values) v.push_back(fmt::format("{:.9g}", value[axis]));
      objects += fmt::format("\tAnimationCurve: {}, \"AnimCurve::\", \"\" {{\n\t\tDefault: {:.9g}\n\t\tKeyVer: 4008\n{}{}\t}}\n",
                             curve, values[0][axis], array("KeyTime", times), array("KeyValueFloat", v));
      connections += fmt::format("\tC: \"OP\",{},{}, \"d|{}\"\n", curve, node, "XYZ"[axis]);
    }
  };
  std::vector<long long> layers;
  for (const auto& [name, clip] : clips) {
    const long long stack = next_id++, layer = next_id++;
    layers.push_back(layer);
    objects += fmt::format("\tAnimationStack: {}, \"AnimStack::{}{}\", \"\" {{\n\t}}\n", stack, settings.stack_prefix, name);
    objects += fmt::format("\tAnimationLayer: {}, \"AnimLayer::BaseLayer\", \"\" {{\n\t}}\n", layer);
    connections += fmt::format("\tC: \"OO\",{},{}\n", layer, stack);
    const Keys keys = keys_of(clip);
    for (int j = 0; j < joints; ++j) {
      curves(layer, model[static_cast<size_t>(j)], "Lcl Rotation", "R", keys.degrees[static_cast<size_t>(j)], clip.motion.fps);
    }
    curves(layer, model[0], "Lcl Translation", "T", keys.translation, clip.motion.fps);
  }
  if (settings.skin) {
    // A triangle skinned to every joint, and a prop beside the armature that every stack moves.
    const long long geometry = next_id++, mesh = next_id++, skin = next_id++, prop = next_id++;
    objects += fmt::format("\tGeometry: {}, \"Geometry::Body\", \"Mesh\" {{\n{}{}\t\tGeometryVersion: 124\n\t}}\n",
                           geometry, array("Vertices", {"0", "0", "0", "10", "0", "0", "0", "10", "0"}),
                           array("PolygonVertexIndex", {"0", "1", "-3"}));
    objects += fmt::format("\tModel: {}, \"Model::Body\", \"Mesh\" {{\n\t\tVersion: 232\n\t}}\n", mesh);
    objects += fmt::format("\tDeformer: {}, \"Deformer::Skin\", \"Skin\" {{\n\t\tVersion: 101\n\t}}\n", skin);
    connections += fmt::format("\tC: \"OO\",{},0\n\tC: \"OO\",{},{}\n\tC: \"OO\",{},{}\n", mesh, geometry, mesh, skin, geometry);
    const std::vector<std::string> identity{"1", "0", "0", "0", "0", "1", "0", "0", "0", "0", "1", "0", "0", "0", "0", "1"};
    const std::string weight = fmt::format("{:.9g}", 1.0 / joints);
    std::vector<bool> leaf(static_cast<size_t>(joints), true);
    for (int j = 1; j < joints; ++j) leaf[static_cast<size_t>(skeleton.parent(j))] = false;
    for (int j = 0; j < joints; ++j) {
      if (!settings.skin_leaves && leaf[static_cast<size_t>(j)]) continue;
      const long long cluster = next_id++;
      objects += fmt::format("\tDeformer: {}, \"SubDeformer::{}\", \"Cluster\" {{\n\t\tVersion: 100\n{}{}{}{}\t}}\n",
                             cluster, skeleton.joint(j).name, array("Indexes", {"0", "1", "2"}),
                             array("Weights", {weight, weight, weight}), array("Transform", identity),
                             array("TransformLink", identity));
      connections += fmt::format("\tC: \"OO\",{},{}\n\tC: \"OO\",{},{}\n", cluster, skin, model[static_cast<size_t>(j)], cluster);
    }
    objects += fmt::format("\tModel: {}, \"Model::Prop\", \"Null\" {{\n\t\tVersion: 232\n\t}}\n", prop);
    connections += fmt::format("\tC: \"OO\",{},0\n", prop);
    for (size_t c = 0; c < clips.size(); ++c) {
      std::vector<Vec3> path;
      for (int f = 0; f < clips[c].second.motion.frame_count; ++f) path.push_back(Vec3(f, 50.0, 0.0));
      curves(layers[c], prop, "Lcl Translation", "T", path, clips[c].second.motion.fps);
    }
  }
  const int time_mode = fps == 30.0 ? 6 : fps == 120.0 ? 1 : 14;  // eFrames30, eFrames120, eCustom
  std::string out = "; FBX 7.4.0 project file\nFBXHeaderExtension:  {\n\tFBXHeaderVersion: 1003\n\tFBXVersion: 7400\n}\n";
  out += fmt::format(
      "GlobalSettings:  {{\n\tVersion: 1000\n\tProperties70:  {{\n"
      "\t\tP: \"UpAxis\", \"int\", \"Integer\", \"\",{}\n\t\tP: \"UpAxisSign\", \"int\", \"Integer\", \"\",{}\n"
      "\t\tP: \"FrontAxis\", \"int\", \"Integer\", \"\",{}\n\t\tP: \"FrontAxisSign\", \"int\", \"Integer\", \"\",1\n"
      "\t\tP: \"CoordAxis\", \"int\", \"Integer\", \"\",0\n\t\tP: \"CoordAxisSign\", \"int\", \"Integer\", \"\",1\n"
      "\t\tP: \"UnitScaleFactor\", \"double\", \"Number\", \"\",{:.9g}\n"
      "\t\tP: \"TimeMode\", \"enum\", \"\", \"\",{}\n\t\tP: \"CustomFrameRate\", \"double\", \"Number\", \"\",{:.9g}\n"
      "\t}}\n}}\n",
      up_axis, settings.up[0] == '-' ? -1 : 1, (up_axis + 1) % 3, settings.unit_scale_factor, time_mode, fps);
  out += "Objects:  {\n" + objects + "}\nConnections:  {\n" + connections + "}\n";
  return out;
}

}  // namespace mg::test
