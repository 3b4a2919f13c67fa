#include "motiongraph/export/fbx_binary.h"

#include <functional>
#include <random>

#include <gtest/gtest.h>

#include "export/fbx_binary_reader.h"

namespace mg {
namespace {

FbxRecord leaf(std::string name, std::vector<FbxValue> values) {
  return FbxRecord{std::move(name), std::move(values), {}, false};
}

TEST(FbxBinary, EveryKindOfValueAndNestingReadsBackAsWritten) {
  FbxRecord objects{"Objects", {}, {}, false};
  objects.add(leaf("Model", {std::int64_t{1234567890123}, std::string("Hips\0\1Model", 11), std::string("LimbNode")}));
  FbxRecord& model = objects.records.back();
  model.add(leaf("Version", {std::int32_t{232}}));
  model.add(FbxRecord{"Properties70", {}, {leaf("P", {std::string("Lcl Translation"), 1.5, -2.25, 1e300})}, false});
  objects.add(leaf("AnimationCurve", {std::vector<std::int64_t>{0, 1539538600, -7}, std::vector<float>{0.5f, -1.0f},
                                      std::vector<std::int32_t>{}, std::vector<double>{3.25}}));
  objects.add(FbxRecord{"AnimationLayer", {std::int64_t{9}}, {}, true});  // an empty block
  objects.add(leaf("", {}));                                              // no name, nothing
  objects.add(leaf(std::string(255, 'n'), {float{-0.0f}, FbxRaw{std::string("\0\xff\x01", 3)}, std::string()}));
  const std::vector<FbxRecord> top{leaf("FileId", {FbxRaw{std::string(16, '\x28')}}), objects,
                                   FbxRecord{"References", {}, {}, true}};
  auto bytes = encode_fbx_binary(top);
  ASSERT_TRUE(bytes.ok()) << bytes.error().message;
  auto back = test::read_fbx_binary(*bytes);
  ASSERT_TRUE(back.ok()) << back.error().message << " at " << back.error().line;
  EXPECT_EQ(*back, top);
}

TEST(FbxBinary, RandomTreesReadBackAsWrittenWithTheFooterOnItsBoundary) {
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> small(0, 4);
  const auto random_value = [&]() -> FbxValue {
    switch (std::uniform_int_distribution<int>(0, 9)(rng)) {
      case 0:
        return static_cast<std::int32_t>(rng());
      case 1:
        return static_cast<std::int64_t>(rng()) << 20;
      case 2:
        return std::uniform_real_distribution<float>(-1e6f, 1e6f)(rng);
      case 3:
        return std::uniform_real_distribution<double>(-1e6, 1e6)(rng);
      case 4:
        return std::string(static_cast<size_t>(small(rng)) * 3, static_cast<char>(rng()));
      case 5:
        return FbxRaw{std::string(static_cast<size_t>(small(rng)), static_cast<char>(rng()))};
      case 6:
        return std::vector<std::int32_t>(static_cast<size_t>(small(rng)), static_cast<std::int32_t>(rng()));
      case 7:
        return std::vector<std::int64_t>(static_cast<size_t>(small(rng)), static_cast<std::int64_t>(rng()));
      case 8:
        return std::vector<float>(static_cast<size_t>(small(rng)), 0.25f);
      default:
        return std::vector<double>(static_cast<size_t>(small(rng)), -0.5);
    }
  };
  std::function<FbxRecord(int)> random_record = [&](int depth) {
    FbxRecord r;
    r.name = std::string(static_cast<size_t>(small(rng)) * 5, static_cast<char>('a' + small(rng)));
    for (int v = small(rng); v > 0; --v) r.values.push_back(random_value());
    if (depth < 3) {
      for (int c = small(rng) - 2; c > 0; --c) r.records.push_back(random_record(depth + 1));
    }
    r.block = r.records.empty() && small(rng) == 0;
    return r;
  };
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<FbxRecord> top;
    for (int n = small(rng); n > 0; --n) top.push_back(random_record(0));
    auto bytes = encode_fbx_binary(top);
    ASSERT_TRUE(bytes.ok());
    auto back = test::read_fbx_binary(*bytes);
    ASSERT_TRUE(back.ok()) << "trial " << trial << ": " << back.error().message << " at " << back.error().line;
    ASSERT_EQ(*back, top) << "trial " << trial;
  }
}

// Long arrays are deflated where that makes them smaller (FBX's encoding 1); short ones, and long
// ones that do not shrink, are written as they are.
TEST(FbxBinary, LongArraysAreDeflatedWhenThatMakesThemSmaller) {
  std::vector<std::int64_t> times;
  for (std::int64_t f = 0; f < 10000; ++f) times.push_back(f * 1539538600);
  std::mt19937 rng(1);
  std::vector<std::int32_t> noise(64);
  for (auto& n : noise) n = static_cast<std::int32_t>(rng());
  const std::vector<FbxRecord> top{leaf("KeyTime", {times}), leaf("Short", {std::vector<float>{1.0f, 2.0f}}),
                                   leaf("Noise", {noise})};
  auto bytes = encode_fbx_binary(top);
  ASSERT_TRUE(bytes.ok());
  EXPECT_LT(bytes->size(), times.size() * sizeof(std::int64_t) * 3 / 4);
  int deflated = 0;
  auto back = test::read_fbx_binary(*bytes, &deflated);
  ASSERT_TRUE(back.ok()) << back.error().message;
  EXPECT_EQ(*back, top);
  EXPECT_EQ(deflated, 1);  // the times; random bytes do not shrink
}

TEST(FbxBinary, ANameOver255BytesIsAnError) {
  const std::vector<FbxRecord> top{FbxRecord{"Objects", {}, {leaf(std::string(256, 'x'), {})}, false}};
  auto bytes = encode_fbx_binary(top);
  ASSERT_FALSE(bytes.ok());
  EXPECT_NE(bytes.error().message.find("over 255 bytes"), std::string::npos) << bytes.error().message;
}

}  // namespace
}  // namespace mg
