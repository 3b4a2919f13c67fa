#include "motiongraph/export/fbx_writer.h"

#include <functional>
#include <limits>
#include <map>
#include <numbers>
#include <random>
#include <set>

#include <gtest/gtest.h>

#include "export/fbx_binary_reader.h"
#include "export/random_motion.h"
#include "motion/max_apart.h"
#include "motion/static_root_bvh.h"
#include "motiongraph/motion/fbx_import.h"
#include "motiongraph/motion/forward_kinematics.h"
#include "test_data.h"

namespace mg {
namespace {

using Affine = Eigen::Affine3d;

std::string text(const FbxValue& v) { return std::get<std::string>(v); }
std::int64_t id(const FbxValue& v) { return std::get<std::int64_t>(v); }

// A Properties70 entry's numbers (from its fifth value on) by its name.
std::map<std::string, std::vector<double>> properties(const FbxRecord& owner) {
  std::map<std::string, std::vector<double>> out;
  const FbxRecord* p70 = test::find_record(owner.records, "Properties70");
  if (!p70) return out;
  for (const FbxRecord& p : p70->records) {
    std::vector<double> numbers;
    for (size_t i = 4; i < p.values.size(); ++i) {
      std::visit(
          [&](const auto& x) {
            using T = std::decay_t<decltype(x)>;
            if constexpr (std::is_arithmetic_v<T>) numbers.push_back(static_cast<double>(x));
          },
          p.values[i]);
    }
    out[text(p.values[0])] = numbers;
  }
  return out;
}

// The file read by the test's own FBX reader and played by FBX's rules alone (a model's local
// transform is Translate(Lcl Translation) * Rotate(Lcl Rotation in its RotationOrder), curves
// replacing the properties they are connected to), not by anything the writer computes.
struct FbxScene {
  struct Model {
    std::string name;
    std::int64_t parent = 0;
    Vec3 translation = Vec3::Zero(), rotation = Vec3::Zero();  // cm, degrees
    int order = 0;
  };
  struct Curves {  // a curve node's three curves
    std::vector<std::int64_t> times[3];
    std::vector<float> values[3];
    std::vector<std::int32_t> flags, flag_keys;  // the X curve's KeyAttrFlags and KeyAttrRefCount
  };
  struct Cluster {
    std::int64_t bone = -1;  // the LimbNode model linked
    std::vector<std::int32_t> indexes;
    Affine transform = Affine::Identity(), transform_link = Affine::Identity();  // centimetres
  };
  std::vector<FbxRecord> records;
  std::map<std::int64_t, Model> models;  // the LimbNodes
  std::vector<Vec3> vertices;            // the stick figure's, centimetres
  std::vector<std::int32_t> polygons;
  std::map<std::int64_t, Cluster> clusters;
  std::vector<std::pair<std::int64_t, Affine>> bind_pose;
  std::vector<std::pair<std::string, std::int64_t>> stacks;                                         // name, id
  std::map<std::int64_t, std::vector<std::tuple<std::int64_t, std::string, Curves>>> stack_curves;  // model, property
  std::map<std::string, std::vector<double>> settings;

  explicit FbxScene(const std::string& bytes) {
    auto read = test::read_fbx_binary(bytes);
    if (!read) {
      ADD_FAILURE() << read.error().message << " at byte " << read.error().line;
      return;
    }
    records = std::move(*read);
    settings = properties(*test::find_record(records, "GlobalSettings"));
    std::map<std::int64_t, const FbxRecord*> objects;
    for (const FbxRecord& r : test::find_record(records, "Objects")->records) objects[id(r.values[0])] = &r;
    const auto name_of = [](const FbxRecord& r) {
      const std::string full = text(r.values[1]);
      return full.substr(0, full.find(std::string("\0\1", 2)));
    };
    const auto matrix = [](const FbxRecord& r) {
      const auto& values = std::get<std::vector<double>>(r.values.at(0));
      Affine m;
      m.matrix() = Eigen::Map<const Eigen::Matrix4d>(values.data());  // column-major
      return m;
    };
    for (const auto& [key, r] : objects) {
      if (r->name == "Geometry") {
        const auto& v = std::get<std::vector<double>>(test::find_record(r->records, "Vertices")->values.at(0));
        for (size_t i = 0; i + 2 < v.size(); i += 3) vertices.emplace_back(v[i], v[i + 1], v[i + 2]);
        polygons =
            std::get<std::vector<std::int32_t>>(test::find_record(r->records, "PolygonVertexIndex")->values.at(0));
      } else if (r->name == "Deformer" && text(r->values[2]) == "Cluster") {
        Cluster& c = clusters[key];
        if (const FbxRecord* indexes = test::find_record(r->records, "Indexes")) {
          c.indexes = std::get<std::vector<std::int32_t>>(indexes->values.at(0));
          EXPECT_EQ(std::get<std::vector<double>>(test::find_record(r->records, "Weights")->values.at(0)),
                    std::vector<double>(c.indexes.size(), 1.0));
        }
        c.transform = matrix(*test::find_record(r->records, "Transform"));
        c.transform_link = matrix(*test::find_record(r->records, "TransformLink"));
      } else if (r->name == "Pose") {
        for (const FbxRecord& node : r->records) {
          if (node.name == "PoseNode") {
            bind_pose.emplace_back(id(test::find_record(node.records, "Node")->values.at(0)),
                                   matrix(*test::find_record(node.records, "Matrix")));
          }
        }
      }
      if (r->name == "Model" && text(r->values[2]) == "LimbNode") {
        auto p = properties(*r);
        Model m;
        m.name = name_of(*r);
        if (p.count("Lcl Translation"))
          m.translation = Vec3(p["Lcl Translation"][0], p["Lcl Translation"][1], p["Lcl Translation"][2]);
        if (p.count("Lcl Rotation"))
          m.rotation = Vec3(p["Lcl Rotation"][0], p["Lcl Rotation"][1], p["Lcl Rotation"][2]);
        if (p.count("RotationOrder")) m.order = static_cast<int>(p["RotationOrder"][0]);
        models[key] = m;
      } else if (r->name == "AnimationStack") {
        stacks.emplace_back(name_of(*r), key);
      }
    }
    // Connections: child -> parent (OO), or child -> parent's property (OP).
    std::map<std::int64_t, std::int64_t> layer_stack, node_layer;
    std::map<std::int64_t, std::pair<std::int64_t, std::string>> node_target;
    std::map<std::int64_t, Curves> node_curves;
    for (const FbxRecord& c : test::find_record(records, "Connections")->records) {
      const std::int64_t child = id(c.values[1]), parent = id(c.values[2]);
      const FbxRecord* from = objects.count(child) ? objects[child] : nullptr;
      const FbxRecord* to = objects.count(parent) ? objects[parent] : nullptr;
      if (!from) continue;
      if (from->name == "Model" && models.count(child)) {
        if (to && to->name == "Deformer") {
          clusters[parent].bone = child;
        } else {
          models[child].parent = parent;
        }
      }
      if (from->name == "AnimationLayer") layer_stack[child] = parent;
      if (from->name == "AnimationCurveNode" && text(c.values[0]) == "OO") node_layer[child] = parent;
      if (from->name == "AnimationCurveNode" && text(c.values[0]) == "OP")
        node_target[child] = {parent, text(c.values[3])};
      if (from->name == "AnimationCurve" && to) {
        const std::string axis = text(c.values[3]);
        const int a = axis == "d|X" ? 0 : axis == "d|Y" ? 1 : 2;
        node_curves[parent].times[a] =
            std::get<std::vector<std::int64_t>>(test::find_record(from->records, "KeyTime")->values[0]);
        node_curves[parent].values[a] =
            std::get<std::vector<float>>(test::find_record(from->records, "KeyValueFloat")->values[0]);
        if (a == 0) {
          node_curves[parent].flags =
              std::get<std::vector<std::int32_t>>(test::find_record(from->records, "KeyAttrFlags")->values[0]);
          node_curves[parent].flag_keys =
              std::get<std::vector<std::int32_t>>(test::find_record(from->records, "KeyAttrRefCount")->values[0]);
        }
      }
    }
    for (const auto& [node, target] : node_target) {
      stack_curves[layer_stack[node_layer[node]]].emplace_back(target.first, target.second, node_curves[node]);
    }
  }

  // World transforms (centimetres) of the models at key `key` of the stack.
  std::map<std::string, Affine> world(std::int64_t stack, size_t key) const {
    std::map<std::int64_t, Model> posed = models;
    if (stack_curves.count(stack)) {
      for (const auto& [model, property, curves] : stack_curves.at(stack)) {
        Vec3 v;
        for (int a = 0; a < 3; ++a) v[a] = curves.values[a].at(key);
        (property == "Lcl Translation" ? posed[model].translation : posed[model].rotation) = v;
      }
    }
    std::map<std::string, Affine> out;
    std::function<Affine(std::int64_t)> world_of = [&](std::int64_t key_id) -> Affine {
      if (key_id == 0) return Affine::Identity();
      const Model& m = posed.at(key_id);
      static const char* kOrders[] = {"XYZ", "XZY", "YZX", "YXZ", "ZXY", "ZYX"};  // applied first to last
      Quat r = Quat::Identity();
      for (const char axis : std::string(kOrders[m.order])) {
        const int a = axis - 'X';
        r = Quat(Eigen::AngleAxisd(m.rotation[a] * std::numbers::pi / 180.0, Vec3::Unit(a))) * r;
      }
      return world_of(m.parent) * Eigen::Translation3d(m.translation) * r;
    };
    for (const auto& [key_id, m] : posed) out[m.name] = world_of(key_id);
    return out;
  }

  // The stick figure's vertices (metres) as the skin deforms them at that key: each by its
  // cluster's joint's world transform times the cluster's Transform (the mesh at the origin).
  std::vector<Vec3> deformed(std::int64_t stack, size_t key) const {
    const auto world_of = world(stack, key);
    std::vector<Vec3> out(vertices.size(), Vec3::Constant(std::numeric_limits<double>::quiet_NaN()));
    for (const auto& [cluster_id, c] : clusters) {
      const Affine m = world_of.at(models.at(c.bone).name) * c.transform;
      for (std::int32_t i : c.indexes) out.at(static_cast<size_t>(i)) = m * vertices[static_cast<size_t>(i)] / 100.0;
    }
    return out;
  }
};

FbxScene written(const Skeleton& skeleton, const Motion& motion, const std::string& name = "take") {
  auto bytes = write_fbx(skeleton, motion, name);
  EXPECT_TRUE(bytes.ok()) << bytes.error().message;
  return FbxScene(bytes.ok() ? *bytes : std::string());
}

// The largest distance (metres) between a joint as the file's first stack plays it and as forward
// kinematics puts it, over every frame.
double max_world_error(const FbxScene& scene, const Skeleton& skeleton, const Motion& motion, size_t stack = 0) {
  const std::vector<Vec3> positions = world_positions(skeleton, motion);
  double worst = 0.0;
  for (int f = 0; f < motion.frame_count; ++f) {
    const auto world = scene.world(scene.stacks.at(stack).second, static_cast<size_t>(f));
    for (int j = 0; j < skeleton.joint_count(); ++j) {
      const Vec3 p = world.at(skeleton.joint(j).name).translation() / 100.0;
      worst = std::max(worst, (p - positions[static_cast<size_t>(f * skeleton.joint_count() + j)]).norm());
    }
  }
  return worst;
}

TEST(FbxWriter, ModelsPlayedByTheFileRulesAreWhereForwardKinematicsPutsTheJoints) {
  for (const char* file : {"cmu/16/16_15.amc", "cmu/16/16_35.amc", "bvh/16_01.bvh", "bvh/131_01.bvh"}) {
    const Clip clip = test::load_data_clip(file);
    const FbxScene scene = written(clip.skeleton, clip.motion);
    ASSERT_EQ(scene.stacks.size(), 1u) << file;
    EXPECT_EQ(scene.stacks[0].first, "take");
    EXPECT_EQ(scene.models.size(),
              static_cast<size_t>(clip.skeleton.joint_count()) + clip.skeleton.static_ancestors().size());
    // Centimetres, y up, z front, right-handed (x across).
    EXPECT_EQ(scene.settings.at("UnitScaleFactor"), std::vector<double>{1.0});
    EXPECT_EQ(scene.settings.at("UpAxis"), std::vector<double>{1.0});
    EXPECT_EQ(scene.settings.at("FrontAxis"), std::vector<double>{2.0});
    EXPECT_EQ(scene.settings.at("CoordAxis"), std::vector<double>{0.0});
    EXPECT_LT(max_world_error(scene, clip.skeleton, clip.motion), 1e-5) << file;  // float32 keys
  }
}

// The stick figure: triangles (a polygon's last index written -(i + 1)), every vertex bound by
// exactly one cluster, a cluster for every joint (its TransformLink the joint at rest), the bind
// pose the models' world transforms at rest, and the figure as the skin deforms it with each
// bone's apexes on its joints in every frame (its tip too where the child's translation moves).
TEST(FbxWriter, TheStickFigureIsSkinnedToTheJoints) {
  std::mt19937 rng(2);
  for (const char* file : {"cmu/16/16_35.amc", "bvh/131_01.bvh", "random"}) {
    const Clip plain = test::load_data_clip(file == std::string("random") ? "cmu/16/16_15.amc" : file);
    const Clip clip = std::string(file).ends_with(".amc") ? plain : test::import_bvh(test::static_root_bvh(plain));
    // Random: every joint's translation animated, so that the bones' tips must follow the children.
    const Motion motion =
        file == std::string("random") ? test::random_motion(clip.skeleton, 20, 30.0, rng) : clip.motion.slice(0, 20);
    const FbxScene scene = written(clip.skeleton, motion);
    ASSERT_FALSE(scene.vertices.empty()) << file;
    ASSERT_EQ(scene.polygons.size(), scene.vertices.size());
    for (size_t i = 0; i < scene.polygons.size(); ++i) {
      EXPECT_EQ(scene.polygons[i], i % 3 == 2 ? -static_cast<std::int32_t>(i) - 1 : static_cast<std::int32_t>(i));
    }
    std::vector<int> bound(scene.vertices.size(), 0);
    for (const auto& [key, c] : scene.clusters) {
      for (std::int32_t i : c.indexes) ++bound.at(static_cast<size_t>(i));
    }
    EXPECT_EQ(std::count(bound.begin(), bound.end(), 1), static_cast<long>(bound.size()));
    // A cluster for every model, the static ancestors' too (as glTF's skin lists every node).
    EXPECT_EQ(scene.clusters.size(),
              static_cast<size_t>(clip.skeleton.joint_count()) + clip.skeleton.static_ancestors().size());
    const auto rest = scene.world(-1, 0);  // no stack: the models' own transforms
    for (const auto& [key, c] : scene.clusters) {
      const Affine& at_rest = rest.at(scene.models.at(c.bone).name);
      EXPECT_TRUE(c.transform_link.isApprox(at_rest, 1e-12));
      EXPECT_TRUE((c.transform * c.transform_link).isApprox(Affine::Identity(), 1e-12));
    }
    EXPECT_EQ(scene.bind_pose.size(), scene.models.size() + 1);  // + the mesh, at the origin
    for (const auto& [model, matrix] : scene.bind_pose) {
      if (scene.models.count(model)) {
        EXPECT_TRUE(matrix.isApprox(rest.at(scene.models.at(model).name), 1e-12));
      } else {
        EXPECT_TRUE(matrix.isApprox(Affine::Identity(), 0.0));
      }
    }
    // The figure's apexes: the vertices standing on a joint at rest stay on it (or on a joint that
    // stood with it) in every frame.
    const int n = clip.skeleton.joint_count();
    std::vector<std::vector<int>> on_joints(scene.vertices.size());
    for (size_t v = 0; v < scene.vertices.size(); ++v) {
      for (int j = 0; j < n; ++j) {
        if ((scene.vertices[v] / 100.0 - rest.at(clip.skeleton.joint(j).name).translation() / 100.0).norm() < 1e-9) {
          on_joints[v].push_back(j);
        }
      }
    }
    const size_t apexes = static_cast<size_t>(
        std::count_if(on_joints.begin(), on_joints.end(), [](const auto& o) { return !o.empty(); }));
    EXPECT_EQ(apexes, scene.vertices.size() / 3);  // one corner of each triangle
    const std::vector<Vec3> positions = world_positions(clip.skeleton, motion);
    for (int f = 0; f < motion.frame_count; f += 7) {
      const std::vector<Vec3> figure = scene.deformed(scene.stacks[0].second, static_cast<size_t>(f));
      for (size_t v = 0; v < figure.size(); ++v) {
        if (on_joints[v].empty()) continue;
        double nearest = std::numeric_limits<double>::infinity();
        for (int j : on_joints[v])
          nearest = std::min(nearest, (figure[v] - positions[static_cast<size_t>(f * n + j)]).norm());
        EXPECT_LT(nearest, 1e-5) << file << " frame " << f << " vertex " << v;
      }
    }
  }
}

TEST(FbxWriter, WithoutTheStickFigureOnlyTheSkeletonAndItsAnimation) {
  const Clip clip = test::load_data_clip("cmu/16/16_15.amc");
  auto bytes = write_fbx(clip.skeleton, clip.motion, "take", FbxWriteSettings{false});
  ASSERT_TRUE(bytes.ok());
  const FbxScene scene(*bytes);
  EXPECT_TRUE(scene.vertices.empty());
  EXPECT_TRUE(scene.clusters.empty());
  EXPECT_TRUE(scene.bind_pose.empty());
  for (const char* type : {"Geometry", "Deformer", "Pose"})
    EXPECT_FALSE(test::find_record(test::find_record(scene.records, "Objects")->records, type)) << type;
  EXPECT_LT(max_world_error(scene, clip.skeleton, clip.motion), 1e-5);
}

TEST(FbxWriter, EachJointKeepsItsOwnRotationOrder) {
  const Clip clip = test::load_data_clip("cmu/16/16_15.amc");
  std::vector<JointDef> joints(clip.skeleton.joints().begin(), clip.skeleton.joints().end());
  const std::vector<ComposeOrder> orders{{Axis::kZ, Axis::kY, Axis::kX}, {Axis::kY, Axis::kZ, Axis::kX},
                                         {Axis::kX, Axis::kZ, Axis::kY}, {Axis::kZ, Axis::kX, Axis::kY},
                                         {Axis::kY, Axis::kX, Axis::kZ}, {Axis::kX, Axis::kY, Axis::kZ}};
  for (size_t j = 0; j < joints.size(); ++j) joints[j].euler_order = orders[j % orders.size()];
  const Skeleton skeleton(joints);
  const FbxScene scene = written(skeleton, clip.motion);
  std::set<int> seen;
  for (const auto& [key, m] : scene.models) seen.insert(m.order);
  EXPECT_EQ(seen.size(), 6u);
  // R = Rz Ry Rx (x applied first) is FBX's XYZ, 0; R = Rx Ry Rz its ZYX, 5.
  for (const auto& [key, m] : scene.models) {
    const int j = *skeleton.find(m.name);
    if (j == 0) continue;  // the root's is its own (below)
    const ComposeOrder& order = joints.at(j).euler_order;
    if (order == orders[0]) {
      EXPECT_EQ(m.order, 0);
    }
    if (order == orders[5]) {
      EXPECT_EQ(m.order, 5);
    }
  }
  EXPECT_LT(max_world_error(scene, skeleton, clip.motion), 1e-5);
}

// The root turns through every heading as the figure travels: its order has the vertical
// outermost (FBX's ZXY: R = Ry Rx Rz), so that the heading is never the middle angle, where Euler
// angles lock. A figure spinning two turns while it leans keys a heading that climbs steadily
// and leans that stay small (in CMU's own XYZ, with the heading in the middle, they jumped at
// every quarter turn).
TEST(FbxWriter, TheRootTurnsAboutTheVerticalOutermost) {
  const Clip clip = test::load_data_clip("cmu/16/16_15.amc");
  Motion motion = clip.motion.slice(0, 80);
  for (int f = 0; f < motion.frame_count; ++f) {
    const double heading = 4.0 * std::numbers::pi * f / motion.frame_count;
    motion.rotations(f)[0] = Quat(Eigen::AngleAxisd(heading, Vec3::UnitY())) *
                             Quat(Eigen::AngleAxisd(0.2, Vec3::UnitX())) * Quat(Eigen::AngleAxisd(-0.1, Vec3::UnitZ()));
  }
  const FbxScene scene = written(clip.skeleton, motion);
  for (const auto& [key, m] : scene.models) {
    if (m.name == clip.skeleton.joint(0).name) {
      EXPECT_EQ(m.order, 4);  // ZXY
    }
  }
  for (const auto& [model, property, curves] : scene.stack_curves.at(scene.stacks[0].second)) {
    if (property != "Lcl Rotation" || scene.models.at(model).name != clip.skeleton.joint(0).name) continue;
    for (size_t k = 0; k < curves.values[1].size(); ++k) {
      EXPECT_NEAR(curves.values[0][k], 0.2 * 180.0 / std::numbers::pi, 1e-3) << k;
      EXPECT_NEAR(curves.values[2][k], -0.1 * 180.0 / std::numbers::pi, 1e-3) << k;
      if (k > 0) {
        EXPECT_NEAR(curves.values[1][k] - curves.values[1][k - 1], 720.0 / motion.frame_count, 1e-3) << k;
      }
    }
  }
  EXPECT_LT(max_world_error(scene, clip.skeleton, motion), 1e-5);
}

TEST(FbxWriter, AStaticRootAboveTheHipsIsWrittenBackAboveThem) {
  const Clip plain = test::load_data_clip("cmu/16/16_15.amc");
  const Vec3 root_at(-2.0, 0.1, 3.0);
  const Quat root_turn(Eigen::AngleAxisd(-2.5, Vec3(0.1, 1.0, 0.2).normalized()));
  const Clip clip = test::import_bvh(test::static_root_bvh(plain, root_at, root_turn));
  ASSERT_EQ(clip.skeleton.static_ancestors().size(), 1u);
  const FbxScene scene = written(clip.skeleton, clip.motion);
  std::int64_t root = -1;
  for (const auto& [key, m] : scene.models) {
    if (m.name == test::kStaticRootName) root = key;
  }
  ASSERT_GE(root, 0);
  EXPECT_EQ(scene.models.at(root).parent, 0);
  for (const auto& [key, m] : scene.models) {
    if (m.name == clip.skeleton.joint(0).name) {
      EXPECT_EQ(m.parent, root);
    }
  }
  for (size_t f : {size_t{0}, static_cast<size_t>(clip.motion.frame_count / 2)}) {
    const Affine world = scene.world(scene.stacks[0].second, f).at(test::kStaticRootName);
    EXPECT_LT((world.translation() / 100.0 - root_at).norm(), 1e-6);
    EXPECT_LT(Quat(world.rotation()).angularDistance(root_turn), 1e-6);
  }
  EXPECT_LT(max_world_error(scene, clip.skeleton, clip.motion), 1e-5);
}

// Random rotations and translations in every frame: the same positions, and Euler keys that never
// jump more than half a turn from one frame to the next (an importer resampling the curves would
// swing the long way round).
TEST(FbxWriter, RandomRotationsGiveContinuousEulerKeysAndTheSamePositions) {
  const Clip cmu = test::load_data_clip("cmu/16/16_15.amc");
  const Clip six_channels = test::import_bvh(test::static_root_bvh(cmu));
  std::mt19937 rng(5);
  for (int round = 0; round < 4; ++round) {
    const Clip& clip = round % 2 == 0 ? cmu : six_channels;
    const Motion motion = test::random_motion(clip.skeleton, 30, 60.0, rng);
    const FbxScene scene = written(clip.skeleton, motion);
    int rotation_nodes = 0;
    for (const auto& [model, property, curves] : scene.stack_curves.at(scene.stacks[0].second)) {
      if (property != "Lcl Rotation") continue;
      ++rotation_nodes;
      for (int a = 0; a < 3; ++a) {
        for (size_t k = 1; k < curves.values[a].size(); ++k)
          EXPECT_LE(std::abs(curves.values[a][k] - curves.values[a][k - 1]), 180.001f);
      }
    }
    EXPECT_GT(rotation_nodes, 20);
    // Kept continuous, keys of random rotations wander far from 0 (hundreds of degrees), where
    // float32 steps are coarser than near it.
    EXPECT_LT(max_world_error(scene, clip.skeleton, motion), 2e-5);
  }
}

TEST(FbxWriter, KeyTimesAreFbxTicksAndTheRateItsTimeMode) {
  const Clip clip = test::load_data_clip("cmu/16/16_15.amc");
  // FBX's TimeMode values: eFrames120 1, eFrames60 3, eFrames30 6, ePAL (25) 10, eFrames24 11,
  // eCustom 14.
  for (const auto& [fps, mode] : std::vector<std::pair<double, double>>{
           {30.0, 6.0}, {120.0, 1.0}, {60.0, 3.0}, {25.0, 10.0}, {24.0, 11.0}, {24.5, 14.0}}) {
    Motion motion = clip.motion.slice(0, 10);
    motion.fps = fps;
    const FbxScene scene = written(clip.skeleton, motion);
    EXPECT_EQ(scene.settings.at("TimeMode"), std::vector<double>{mode}) << fps;
    EXPECT_EQ(scene.settings.at("CustomFrameRate"), std::vector<double>{fps});
    const auto& [model, property, curves] = scene.stack_curves.at(scene.stacks[0].second).front();
    ASSERT_EQ(curves.times[0].size(), 10u);
    for (int f = 0; f < 10; ++f)
      EXPECT_NEAR(static_cast<double>(curves.times[0][f]), f * 46186158000.0 / fps, 0.5) << fps;
    // Keys interpolated linearly between frames: FBX's eInterpolationLinear (0x4), one attribute
    // shared by every key.
    EXPECT_EQ(curves.flags, std::vector<std::int32_t>{0x4});
    EXPECT_EQ(curves.flag_keys, std::vector<std::int32_t>{10});
    EXPECT_EQ(scene.settings.at("TimeSpanStop"), std::vector<double>{static_cast<double>(curves.times[0].back())});
  }
}

// A character's animation set: a stack per motion, each keying the same joints at its own rate
// (the file's TimeMode is the first's), read back by Open Asset Import Library (the project's FBX
// reader) to the motions' own joint positions and rates.
TEST(FbxWriter, SeveralMotionsAreAStackEachThatAnFbxReaderReadsBack) {
  const Clip walk = test::load_data_clip("cmu/16/16_15.amc");
  Clip jog = test::load_data_clip("cmu/16/16_35.amc");
  jog.motion.fps = 30.0;  // its frames played at another rate than the walk's 120
  const std::vector<FbxAnimation> animations{{"walk", &walk.motion}, {"jog", &jog.motion}, {"walk", &walk.motion}};
  auto bytes = write_fbx(walk.skeleton, animations);
  ASSERT_TRUE(bytes.ok()) << bytes.error().message;
  const FbxScene scene(*bytes);
  ASSERT_EQ(scene.stacks.size(), 3u);
  EXPECT_EQ(scene.stacks[0].first, "walk");
  EXPECT_EQ(scene.stacks[1].first, "jog");
  EXPECT_EQ(scene.stacks[2].first, "walk_2");
  EXPECT_EQ(scene.stack_curves.at(scene.stacks[0].second).size(), scene.stack_curves.at(scene.stacks[1].second).size());
  EXPECT_LT(max_world_error(scene, walk.skeleton, jog.motion, 1), 1e-5);
  EXPECT_EQ(scene.settings.at("TimeMode"), std::vector<double>{1.0});  // 120, the first's
  for (size_t stack = 0; stack < 2; ++stack) {
    const double fps = stack == 0 ? 120.0 : 30.0;
    const auto& [model, property, curves] = scene.stack_curves.at(scene.stacks[stack].second).front();
    for (size_t f = 0; f < curves.times[0].size(); ++f) {
      EXPECT_EQ(curves.times[0][f], static_cast<std::int64_t>(f) * static_cast<std::int64_t>(46186158000.0 / fps))
          << stack;
    }
  }

  auto clips = clips_from_fbx(*bytes, "set.fbx", FbxImportSettings{});
  ASSERT_TRUE(clips.ok()) << clips.error().message;
  ASSERT_EQ(clips->size(), 3u);
  EXPECT_EQ((*clips)[1].name, "jog");
  for (size_t i = 0; i < 3; ++i) {
    const Clip& source = i == 1 ? jog : walk;
    EXPECT_EQ((*clips)[i].motion.fps, source.motion.fps);
    EXPECT_LT(test::max_apart(source, (*clips)[i]), 1e-5) << i;
  }
}

TEST(FbxWriter, WithoutFramesTheSkeletonIsStillWritten) {
  const Clip clip = test::load_data_clip("cmu/16/16_15.amc");
  const FbxScene still = written(clip.skeleton, clip.motion.slice(0, 0));
  EXPECT_TRUE(still.stacks.empty());
  ASSERT_EQ(still.models.size(), static_cast<size_t>(clip.skeleton.joint_count()));
  // At rest each joint stands at its offset from its parent (the root over the origin).
  const auto world = still.world(0, 0);
  for (int j = 1; j < clip.skeleton.joint_count(); ++j) {
    const JointDef& joint = clip.skeleton.joint(j);
    const Vec3 offset =
        world.at(joint.name).translation() - world.at(clip.skeleton.joint(joint.parent).name).translation();
    EXPECT_LT((offset / 100.0 - joint.rest_offset_m).norm(), 1e-9) << joint.name;
  }
}

// FBX names are UTF-8 and end at the bytes 0 and 1 (which separate a name from its class): a
// name in Latin-1 gets U+FFFD for the bytes that are not UTF-8, 0 and 1 become '_', and names made
// alike so are told apart.
TEST(FbxWriter, NamesAreRepairedAndKeptApart) {
  const Clip clip = test::load_data_clip("cmu/16/16_15.amc");
  std::vector<JointDef> joints(clip.skeleton.joints().begin(), clip.skeleton.joints().end());
  joints[1].name =
      "H\xfc"
      "fte";
  joints[2].name =
      "H\xe4"
      "fte";
  joints[3].name = std::string("a\0\1Model", 8);
  auto bytes = write_fbx(Skeleton(joints), clip.motion,
                         std::string("H\xfc"
                                     "pfen\0\1x",
                                     9));
  ASSERT_TRUE(bytes.ok());
  const FbxScene scene(*bytes);
  EXPECT_EQ(scene.stacks.at(0).first,
            "H\xef\xbf\xbd"
            "pfen__x");
  std::set<std::string> names;
  for (const auto& [key, m] : scene.models) names.insert(m.name);
  EXPECT_EQ(names.size(), scene.models.size());
  for (const char* name : {"H\xef\xbf\xbd"
                           "fte",
                           "H\xef\xbf\xbd"
                           "fte_2",
                           "a__Model"})
    EXPECT_TRUE(names.count(name)) << name;
}

TEST(FbxWriter, AnAnimationWithoutANameOrThatDoesNotFitIsAnError) {
  const Clip clip = test::load_data_clip("cmu/16/16_15.amc");
  auto unnamed = write_fbx(clip.skeleton, clip.motion, "");
  ASSERT_FALSE(unnamed.ok());
  EXPECT_EQ(unnamed.error().message, "every FBX animation needs a name");
  const Clip other = test::with_fingers(clip);  // more joints
  auto misfit = write_fbx(clip.skeleton, other.motion, "other");
  ASSERT_FALSE(misfit.ok());
  EXPECT_EQ(misfit.error().message.rfind("animation 'other': ", 0), 0u) << misfit.error().message;
}

}  // namespace
}  // namespace mg
