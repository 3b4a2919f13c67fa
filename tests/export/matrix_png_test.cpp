// The distance-matrix picture: PNG size from its IHDR chunk, pixels decoded with stb_image
// (dark low values, undefined colour, clip-boundary lines, transition crosses), block
// minima, and the full-matrix and block-minimum paths giving the same bytes.
#include "motiongraph/export/matrix_png.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

// Debian's libstb-dev: compiled here with internal linkage (no link to libstb needed).
#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_STATIC
#define STBI_ONLY_PNG
#define STBI_NO_STDIO
#include <stb/stb_image.h>

namespace mg {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// A full matrix with a valley along the diagonal: |row - col| + 1.
std::vector<float> valley_matrix(int n) {
  std::vector<float> m(static_cast<size_t>(n) * n);
  for (int r = 0; r < n; ++r) {
    for (int c = 0; c < n; ++c) m[static_cast<size_t>(r) * n + c] = static_cast<float>(std::abs(r - c) + 1);
  }
  return m;
}

void set(std::vector<float>& m, int n, int row, int col, float value) { m[static_cast<size_t>(row) * n + col] = value; }

uint32_t big_endian_u32(const std::string& bytes, size_t at) {
  uint32_t value = 0;
  for (size_t i = 0; i < 4; ++i) value = (value << 8) | static_cast<unsigned char>(bytes[at + i]);
  return value;
}

// Width and height from the IHDR chunk (the first chunk, right after the 8-byte signature).
std::pair<int, int> png_size(const std::string& png) {
  EXPECT_GE(png.size(), 33u);
  EXPECT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  EXPECT_EQ(png.substr(12, 4), "IHDR");
  EXPECT_EQ(png[24], 8) << "bit depth";
  EXPECT_EQ(png[25], 2) << "colour type RGB";
  return {static_cast<int>(big_endian_u32(png, 16)), static_cast<int>(big_endian_u32(png, 20))};
}

RgbImage decode(const std::string& png) {
  int width = 0;
  int height = 0;
  int channels = 0;
  stbi_uc* pixels = stbi_load_from_memory(reinterpret_cast<const stbi_uc*>(png.data()), static_cast<int>(png.size()),
                                          &width, &height, &channels, 3);
  EXPECT_NE(pixels, nullptr) << stbi_failure_reason();
  RgbImage image;
  if (!pixels) return image;
  image.width = width;
  image.height = height;
  image.pixels.assign(pixels, pixels + static_cast<size_t>(width) * height * 3);
  stbi_image_free(pixels);
  return image;
}

double luminance(Rgb c) { return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]; }

Rgb blended_with_boundary(Rgb c) {
  Rgb out;
  for (int i = 0; i < 3; ++i) out[i] = static_cast<uint8_t>((c[i] + kMatrixBoundaryRgb[i] + 1) / 2);
  return out;
}

TEST(MatrixPng, SizeIsTheFrameCountUpToTheMaximumSide) {
  const std::vector<float> small = valley_matrix(40);
  auto png = matrix_png(small, 40, {}, {}, {});
  ASSERT_TRUE(png) << png.error().to_string();
  EXPECT_EQ(png_size(*png), std::make_pair(40, 40));

  // 250 frames, at most 100 pixels: blocks of 3 frames, 84 pixels.
  MatrixPngSettings settings;
  settings.max_side_px = 100;
  const std::vector<float> large = valley_matrix(250);
  png = matrix_png(large, 250, {}, {}, settings);
  ASSERT_TRUE(png) << png.error().to_string();
  EXPECT_EQ(png_size(*png), std::make_pair(84, 84));
  EXPECT_EQ(min_matrix_block(250, 100), 3);
  EXPECT_EQ(min_matrix_block(100, 100), 1);
  EXPECT_EQ(min_matrix_block(201, 100), 3);
}

TEST(MatrixPng, PixelsShowValuesUndefinedEntriesBoundariesAndTransitions) {
  const int n = 60;
  std::vector<float> m = valley_matrix(n);
  set(m, n, 10, 40, 0.0f);   // a deep minimum far from the diagonal
  set(m, n, 40, 10, 59.0f);  // as high as the far corners
  for (int r = 0; r < 5; ++r) {
    for (int c = 0; c < n; ++c) set(m, n, r, c, kNaN);  // undefined rows
  }
  const std::vector<int> clip_starts = {0, 30};
  const std::vector<Transition> transitions = {{45, 15}};

  auto png = matrix_png(m, n, clip_starts, transitions, {});
  ASSERT_TRUE(png) << png.error().to_string();
  const RgbImage image = decode(*png);
  ASSERT_EQ(image.width, n);
  ASSERT_EQ(image.height, n);

  // Low dark, high light: pixel (x = column, y = row).
  EXPECT_LT(luminance(image.at(40, 10)), luminance(image.at(10, 40)));
  EXPECT_EQ(image.at(40, 10), matrix_ramp(0.0)) << "the smallest value gets the darkest colour";
  EXPECT_LT(luminance(image.at(21, 20)), luminance(image.at(50, 20))) << "the diagonal valley is darker";

  // Undefined entries; and a block above the pruned stage's ceiling.
  std::vector<float> above = m;
  set(above, n, 50, 10, std::numeric_limits<float>::infinity());
  auto with_above = matrix_png(above, n, clip_starts, {}, {});
  ASSERT_TRUE(with_above);
  EXPECT_EQ(decode(*with_above).at(10, 50), kMatrixAboveCeilingRgb);
  EXPECT_NE(kMatrixAboveCeilingRgb, kMatrixUndefinedRgb);
  EXPECT_EQ(image.at(20, 2), kMatrixUndefinedRgb);
  EXPECT_EQ(image.at(59, 4), kMatrixUndefinedRgb);
  EXPECT_NE(image.at(20, 5), kMatrixUndefinedRgb);

  // Clip start 30: row 30 and column 30 blended toward white; their neighbours untouched.
  // Entry (row 20, col 31) has value 12 and (row 20, col 29) value 10: compare with the ramp
  // by rendering without boundaries.
  auto plain = render_matrix_picture(BlockMinMatrix(0, 1).view(), {}, {}, {});  // empty: an error
  EXPECT_FALSE(plain);
  BlockMinMatrix minima(n, 1024);
  for (int r = 0; r < n; ++r) minima.add_row(r, 0, std::span(m).subspan(static_cast<size_t>(r) * n, n));
  auto base = render_matrix_picture(minima.view(), {}, {}, {});
  ASSERT_TRUE(base) << base.error().to_string();
  for (int i = 5; i < n; ++i) {
    if (i == 30) continue;
    EXPECT_EQ(image.at(30, i), blended_with_boundary(base->at(30, i))) << "column 30, row " << i;
    EXPECT_EQ(image.at(i, 30), blended_with_boundary(base->at(i, 30))) << "row 30, column " << i;
    EXPECT_EQ(image.at(29, i), base->at(29, i));
    EXPECT_EQ(image.at(31, i), base->at(31, i));
  }
  EXPECT_EQ(image.at(0, 20), base->at(0, 20)) << "frame 0 draws no line";

  // The transition (row 45, column 15): a red cross at x = 15, y = 45.
  for (int k = -2; k <= 2; ++k) {
    EXPECT_EQ(image.at(15 + k, 45), kMatrixTransitionRgb);
    EXPECT_EQ(image.at(15, 45 + k), kMatrixTransitionRgb);
  }
  EXPECT_NE(image.at(16, 46), kMatrixTransitionRgb) << "a '+', not a square";
  EXPECT_NE(image.at(18, 45), kMatrixTransitionRgb);
}

TEST(MatrixPng, OutliersDoNotFlattenTheRamp) {
  const int n = 50;
  std::vector<float> m = valley_matrix(n);
  set(m, n, 0, 1, 1e9f);
  auto image = render_matrix_picture(
      MinMatrixView{m, n, 1}, {}, {}, {});
  ASSERT_TRUE(image) << image.error().to_string();
  // The far corner (value 50, above the 99th percentile of the rest) is the lightest colour,
  // and a middling value sits well inside the ramp, not crushed to the dark end.
  EXPECT_EQ(image->at(49, 0), matrix_ramp(1.0));
  EXPECT_EQ(image->at(1, 0), matrix_ramp(1.0));
  EXPECT_GT(luminance(image->at(25, 0)), luminance(matrix_ramp(0.3)));
}

TEST(MatrixPng, DownsamplingKeepsTheBlockMinimum) {
  const int n = 300;
  std::vector<float> m(static_cast<size_t>(n) * n, 10.0f);
  for (size_t i = 0; i < m.size(); i += 7) m[i] = 20.0f;
  set(m, n, 150, 200, 0.5f);  // a single low entry: pixel (200 / 3, 150 / 3)
  set(m, n, 151, 13, kNaN);   // one undefined entry in a block of finite ones
  for (int r = 294; r < 297; ++r) {
    for (int c = 3; c < 6; ++c) set(m, n, r, c, kNaN);  // a whole undefined block: pixel (1, 98)
  }
  MatrixPngSettings settings;
  settings.max_side_px = 100;
  BlockMinMatrix minima(n, settings.max_side_px);
  ASSERT_EQ(minima.block(), 3);
  ASSERT_EQ(minima.side(), 100);
  for (int r = 0; r < n; ++r) minima.add_row(r, 0, std::span(m).subspan(static_cast<size_t>(r) * n, n));
  const auto values = minima.values();
  EXPECT_EQ(values[50 * 100 + 66], 0.5f);
  EXPECT_EQ(values[50 * 100 + 4], 10.0f) << "NaN does not hide a finite minimum";
  EXPECT_TRUE(std::isnan(values[98 * 100 + 1]));

  auto png = matrix_png(m, n, {}, {}, settings);
  ASSERT_TRUE(png) << png.error().to_string();
  const RgbImage image = decode(*png);
  EXPECT_EQ(image.at(66, 50), matrix_ramp(0.0));
  EXPECT_EQ(image.at(1, 98), kMatrixUndefinedRgb);
  EXPECT_NE(image.at(66, 51), matrix_ramp(0.0));
}

TEST(MatrixPng, BlockMinimaFoldedPieceByPieceGiveTheSameBytesAsTheFullMatrix) {
  const int n = 230;
  std::vector<float> m = valley_matrix(n);
  for (int r = 0; r < n; ++r) {
    for (int c = 0; c < n; ++c) {
      if ((r * 31 + c * 17) % 97 == 0) set(m, n, r, c, 0.25f * static_cast<float>((r + c) % 5));
      if (r < 3 || c > n - 3) set(m, n, r, c, kNaN);
    }
  }
  const std::vector<int> clip_starts = {0, 77, 150};
  const std::vector<Transition> transitions = {{10, 100}, {200, 5}, {229, 229}};
  MatrixPngSettings settings;
  settings.max_side_px = 64;

  auto full = matrix_png(m, n, clip_starts, transitions, settings);
  ASSERT_TRUE(full) << full.error().to_string();

  // Two "threads": even rows entry by entry, odd rows in pieces of columns; then merged.
  BlockMinMatrix even(n, settings.max_side_px);
  BlockMinMatrix odd(n, settings.max_side_px);
  for (int r = 0; r < n; ++r) {
    if (r % 2 == 0) {
      for (int c = n - 1; c >= 0; --c) even.add(r, c, m[static_cast<size_t>(r) * n + c]);
    } else {
      for (int c0 = 0; c0 < n; c0 += 50) {
        const int count = std::min(50, n - c0);
        odd.add_row(r, c0, std::span(m).subspan(static_cast<size_t>(r) * n + c0, count));
      }
    }
  }
  even.merge(odd);
  auto folded = matrix_png(even.view(), clip_starts, transitions, settings);
  ASSERT_TRUE(folded) << folded.error().to_string();
  EXPECT_EQ(*folded, *full);
  EXPECT_EQ(png_size(*folded), std::make_pair(58, 58));  // ceil(230 / ceil(230 / 64) = 4)
}

TEST(MatrixPng, CoarsenedBlockMinimaAreTheBlockMinimaOfTheFullMatrix) {
  const int n = 230;
  std::vector<float> m = valley_matrix(n);
  for (int r = 0; r < n; ++r) {
    for (int c = 0; c < n; ++c) {
      if ((r * 13 + c * 7) % 89 == 0) set(m, n, r, c, 0.5f * static_cast<float>((r * c) % 7));
      if (r > n - 4 || (c < 9 && r < 9)) set(m, n, r, c, kNaN);  // undefined rows and a whole block
    }
  }
  BlockMinMatrix fine(n, 100);  // block 3, 77 pixels a side
  for (int r = 0; r < n; ++r) fine.add_row(r, 0, std::span(m).subspan(static_cast<size_t>(r) * n, n));
  ASSERT_EQ(fine.block(), 3);
  for (const int max_side : {100, 40, 20, 7, 1}) {
    const MinMatrix coarse = coarsen_min_matrix(fine.view(), n, max_side);
    // The smallest multiple of 3 frames per pixel that fits.
    int block = 3;
    while ((n + block - 1) / block > max_side) block += 3;
    ASSERT_EQ(coarse.block, block) << max_side;
    ASSERT_EQ(coarse.side, (n + block - 1) / block) << max_side;
    ASSERT_LE(coarse.side, max_side);
    // Reference: each pixel the minimum of its block of the full matrix, entry by entry.
    for (int i = 0; i < coarse.side; ++i) {
      for (int j = 0; j < coarse.side; ++j) {
        float expected = kNaN;
        for (int r = i * block; r < std::min(n, (i + 1) * block); ++r) {
          for (int c = j * block; c < std::min(n, (j + 1) * block); ++c) {
            const float v = m[static_cast<size_t>(r) * n + c];
            if (v < expected || std::isnan(expected)) expected = v;
          }
        }
        const float got = coarse.values[static_cast<size_t>(i) * coarse.side + j];
        if (std::isnan(expected)) {
          EXPECT_TRUE(std::isnan(got)) << i << "," << j;
        } else {
          EXPECT_EQ(got, expected) << i << "," << j;
        }
      }
    }
  }
}

TEST(MatrixPng, EncodedPixelsDecodeExactly) {
  RgbImage image;
  image.width = 5;
  image.height = 3;
  for (int i = 0; i < 15 * 3; ++i) image.pixels.push_back(static_cast<uint8_t>(i * 17));
  auto png = encode_png(image);
  ASSERT_TRUE(png) << png.error().to_string();
  const RgbImage back = decode(*png);
  EXPECT_EQ(back.width, 5);
  EXPECT_EQ(back.height, 3);
  EXPECT_EQ(back.pixels, image.pixels);
}

TEST(MatrixPng, RampRunsFromDarkToLight) {
  double previous = -1.0;
  for (int i = 0; i <= 100; ++i) {
    const double l = luminance(matrix_ramp(i / 100.0));
    EXPECT_GE(l, previous) << "t = " << i / 100.0;
    previous = l;
  }
  EXPECT_EQ(matrix_ramp(-1.0), matrix_ramp(0.0));
  EXPECT_EQ(matrix_ramp(std::nan("")), matrix_ramp(0.0));
  EXPECT_EQ(matrix_ramp(7.0), matrix_ramp(1.0));
  for (int i = 0; i <= 100; ++i) {
    EXPECT_NE(matrix_ramp(i / 100.0), kMatrixUndefinedRgb);
    EXPECT_NE(matrix_ramp(i / 100.0), kMatrixTransitionRgb);
  }
}

TEST(MatrixPng, InconsistentInputsAreErrors) {
  const std::vector<float> m = valley_matrix(10);
  MatrixPngSettings bad;
  bad.max_side_px = 0;
  EXPECT_FALSE(bad.validate());
  EXPECT_FALSE(matrix_png(m, 10, {}, {}, bad));
  bad = {};
  bad.high_percentile = 0.0;
  EXPECT_FALSE(bad.validate());
  bad = {};
  bad.marker_radius_px = -1;
  EXPECT_FALSE(bad.validate());
  EXPECT_TRUE(MatrixPngSettings{}.validate());

  auto wrong_size = matrix_png(m, 9, {}, {}, {});
  ASSERT_FALSE(wrong_size);
  EXPECT_NE(wrong_size.error().message.find("100 values for a 9 x 9"), std::string::npos) << wrong_size.error().message;
  const std::vector<Transition> outside = {{3, 10}};
  auto transition = matrix_png(m, 10, {}, outside, {});
  ASSERT_FALSE(transition);
  EXPECT_NE(transition.error().message.find("3 -> 10"), std::string::npos) << transition.error().message;
  const std::vector<int> starts = {0, -1};
  EXPECT_FALSE(matrix_png(m, 10, starts, {}, {}));

  MatrixPngSettings small;
  small.max_side_px = 5;
  auto too_large = matrix_png(MinMatrixView{m, 10, 1}, {}, {}, small);
  ASSERT_FALSE(too_large);
  EXPECT_NE(too_large.error().message.find("max_side_px"), std::string::npos);
  EXPECT_FALSE(matrix_png(MinMatrixView{m, 9, 1}, {}, {}, {}));
  EXPECT_FALSE(matrix_png(MinMatrixView{m, 10, 0}, {}, {}, {}));
  EXPECT_FALSE(matrix_png(std::span<const float>(), 0, {}, {}, {}));
}

}  // namespace
}  // namespace mg
