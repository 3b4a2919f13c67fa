// The distance-matrix picture: block-minimum downsampling, viridis colouring clamped at a
// high percentile, clip boundaries and transition markers, PNG encoding. See matrix_png.h.
#include "motiongraph/export/matrix_png.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

#include <fmt/format.h>

// stb_image_write compiled into this file only, with internal linkage (no clash with any
// other user of stb, no need to link Debian's libstb) and without its stdio functions: the
// PNG is written to memory, only io/file.h touches the disk.
#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_WRITE_STATIC
#define STBI_WRITE_NO_STDIO
#include <stb_image_write.h>

namespace mg {
namespace {

// viridis (matplotlib), sampled at 10 evenly spaced points; linear in between.
constexpr std::array<Rgb, 10> kViridis = {{
    {0x44, 0x01, 0x54}, {0x48, 0x28, 0x78}, {0x3E, 0x4A, 0x89}, {0x31, 0x68, 0x8E}, {0x26, 0x82, 0x8E},
    {0x1F, 0x9E, 0x89}, {0x35, 0xB7, 0x79}, {0x6D, 0xCD, 0x59}, {0xB4, 0xDE, 0x2C}, {0xFD, 0xE7, 0x25},
}};

Error picture_error(std::string message) { return Error{"", 0, "distance-matrix picture: " + std::move(message)}; }

// Value range of the colour ramp: the smallest finite value and the percentile; nullopt-like
// (low > high) when no value is finite.
struct ValueRange {
  float low = 0.0f;
  float high = -1.0f;
};

ValueRange value_range(std::span<const float> values, double percentile) {
  std::vector<float> finite;
  finite.reserve(values.size());
  for (const float value : values) {
    if (std::isfinite(value)) finite.push_back(value);
  }
  if (finite.empty()) return {};
  ValueRange range;
  range.low = *std::min_element(finite.begin(), finite.end());
  // Nearest rank: the smallest value with at least `percentile` % of the values at or below it.
  const double rank = std::ceil(percentile / 100.0 * static_cast<double>(finite.size()));
  const size_t index = static_cast<size_t>(std::clamp(rank, 1.0, static_cast<double>(finite.size()))) - 1;
  std::nth_element(finite.begin(), finite.begin() + static_cast<std::ptrdiff_t>(index), finite.end());
  range.high = finite[index];
  return range;
}

void set_pixel(RgbImage& image, int x, int y, Rgb colour) {
  if (x < 0 || y < 0 || x >= image.width || y >= image.height) return;
  std::uint8_t* p = &image.pixels[(static_cast<size_t>(y) * image.width + x) * 3];
  p[0] = colour[0];
  p[1] = colour[1];
  p[2] = colour[2];
}

void blend_pixel(RgbImage& image, int x, int y, Rgb colour) {
  std::uint8_t* p = &image.pixels[(static_cast<size_t>(y) * image.width + x) * 3];
  for (int c = 0; c < 3; ++c) p[c] = static_cast<std::uint8_t>((p[c] + colour[c] + 1) / 2);
}

void append_to_string(void* context, void* data, int size) {
  static_cast<std::string*>(context)->append(static_cast<const char*>(data), static_cast<size_t>(size));
}

}  // namespace

Status MatrixPngSettings::validate() const {
  if (max_side_px < 1 || max_side_px > 16384) {
    return picture_error("max_side_px must be between 1 and 16384");
  }
  if (!(high_percentile > 0.0 && high_percentile <= 100.0)) {
    return picture_error("high_percentile must be in (0, 100]");
  }
  if (marker_radius_px < 0 || marker_radius_px > 64) {
    return picture_error("marker_radius_px must be between 0 and 64");
  }
  return Ok{};
}

int min_matrix_block(int frame_count, int max_side_px) {
  assert(max_side_px >= 1);
  if (frame_count <= max_side_px) return 1;
  return (frame_count + max_side_px - 1) / max_side_px;
}

MinMatrix coarsen_min_matrix(const MinMatrixView& matrix, int frame_count, int max_side_px) {
  assert(max_side_px >= 1 && matrix.block >= 1);
  const int factor = std::max(1, min_matrix_block((frame_count + matrix.block - 1) / matrix.block, max_side_px));
  MinMatrix out;
  out.block = matrix.block * factor;
  out.side = (matrix.side + factor - 1) / factor;
  out.values.assign(static_cast<size_t>(out.side) * out.side, std::numeric_limits<float>::quiet_NaN());
  for (int row = 0; row < matrix.side; ++row) {
    for (int col = 0; col < matrix.side; ++col) {
      const float value = matrix.values[static_cast<size_t>(row) * matrix.side + col];
      float& cell = out.values[static_cast<size_t>(row / factor) * out.side + col / factor];
      if (value < cell || std::isnan(cell)) cell = value;
    }
  }
  return out;
}

BlockMinMatrix::BlockMinMatrix(int frame_count, int max_side_px)
    : frame_count_(std::max(frame_count, 0)),
      block_(min_matrix_block(frame_count_, max_side_px)),
      side_((frame_count_ + block_ - 1) / block_),
      values_(static_cast<size_t>(side_) * side_, std::nanf("")) {}

void BlockMinMatrix::add_row(int row, int first_col, std::span<const float> values) {
  assert(row >= 0 && row < frame_count_ && first_col >= 0);
  assert(first_col + static_cast<int>(values.size()) <= frame_count_);
  float* cells = values_.data() + static_cast<size_t>(row / block_) * side_;
  int col = first_col;
  for (const float value : values) {
    float& cell = cells[col / block_];
    if (value < cell || std::isnan(cell)) cell = value;
    ++col;
  }
}

void BlockMinMatrix::merge(const BlockMinMatrix& other) {
  assert(other.frame_count_ == frame_count_ && other.block_ == block_);
  for (size_t i = 0; i < values_.size(); ++i) {
    const float value = other.values_[i];
    if (value < values_[i] || std::isnan(values_[i])) values_[i] = value;
  }
}

Rgb RgbImage::at(int x, int y) const {
  assert(x >= 0 && y >= 0 && x < width && y < height);
  const std::uint8_t* p = &pixels[(static_cast<size_t>(y) * width + x) * 3];
  return {p[0], p[1], p[2]};
}

Rgb matrix_ramp(double t) {
  if (!(t > 0.0)) return kViridis.front();  // also NaN
  if (t >= 1.0) return kViridis.back();
  const double position = t * static_cast<double>(kViridis.size() - 1);
  const size_t i = static_cast<size_t>(position);
  const double f = position - static_cast<double>(i);
  Rgb colour;
  for (int c = 0; c < 3; ++c) {
    const double value = (1.0 - f) * kViridis[i][c] + f * kViridis[i + 1][c];
    colour[c] = static_cast<std::uint8_t>(std::lround(value));
  }
  return colour;
}

Result<RgbImage> render_matrix_picture(const MinMatrixView& matrix, std::span<const int> clip_first_frames,
                                       std::span<const Transition> transitions,
                                       const MatrixPngSettings& settings) {
  if (Status valid = settings.validate(); !valid) return valid.error();
  if (matrix.side < 1) return picture_error("the matrix is empty");
  if (matrix.block < 1) return picture_error(fmt::format("block must be at least 1, not {}", matrix.block));
  if (matrix.values.size() != static_cast<size_t>(matrix.side) * matrix.side) {
    return picture_error(fmt::format("{} values for a {} x {} matrix", matrix.values.size(), matrix.side, matrix.side));
  }
  if (matrix.side > settings.max_side_px) {
    return picture_error(fmt::format("the matrix is {} pixels a side, more than max_side_px = {}", matrix.side,
                                     settings.max_side_px));
  }
  // Frames the pixels cover (the last block may be partial, so this bounds N from above).
  const long long frame_limit = static_cast<long long>(matrix.side) * matrix.block;
  for (const int frame : clip_first_frames) {
    if (frame < 0 || frame >= frame_limit) return picture_error(fmt::format("clip start frame {} is outside the matrix", frame));
  }
  for (const Transition& t : transitions) {
    if (t.from_frame < 0 || t.from_frame >= frame_limit || t.to_frame < 0 || t.to_frame >= frame_limit) {
      return picture_error(fmt::format("transition {} -> {} is outside the matrix", t.from_frame, t.to_frame));
    }
  }

  RgbImage image;
  image.width = matrix.side;
  image.height = matrix.side;
  image.pixels.resize(static_cast<size_t>(image.width) * image.height * 3);

  // Values.
  const ValueRange range = value_range(matrix.values, settings.high_percentile);
  const double span = static_cast<double>(range.high) - static_cast<double>(range.low);
  for (int y = 0; y < matrix.side; ++y) {
    for (int x = 0; x < matrix.side; ++x) {
      const float value = matrix.values[static_cast<size_t>(y) * matrix.side + x];
      if (value == std::numeric_limits<float>::infinity()) {
        set_pixel(image, x, y, kMatrixAboveCeilingRgb);
      } else if (!std::isfinite(value)) {
        set_pixel(image, x, y, kMatrixUndefinedRgb);
      } else {
        const double t = span > 0.0 ? (static_cast<double>(value) - range.low) / span : 0.0;
        set_pixel(image, x, y, matrix_ramp(t));
      }
    }
  }

  // Clip boundaries: the row and the column of each clip's first frame, once per pixel.
  std::vector<bool> boundary(static_cast<size_t>(matrix.side), false);
  for (const int frame : clip_first_frames) {
    if (frame > 0) boundary[static_cast<size_t>(frame / matrix.block)] = true;
  }
  for (int y = 0; y < matrix.side; ++y) {
    for (int x = 0; x < matrix.side; ++x) {
      if (boundary[static_cast<size_t>(x)] || boundary[static_cast<size_t>(y)]) {
        blend_pixel(image, x, y, kMatrixBoundaryRgb);
      }
    }
  }

  // Transitions: a "+" centred on the pixel holding (from_frame, to_frame).
  for (const Transition& t : transitions) {
    const int x = t.to_frame / matrix.block;
    const int y = t.from_frame / matrix.block;
    for (int k = -settings.marker_radius_px; k <= settings.marker_radius_px; ++k) {
      set_pixel(image, x + k, y, kMatrixTransitionRgb);
      set_pixel(image, x, y + k, kMatrixTransitionRgb);
    }
  }
  return image;
}

Result<std::string> encode_png(const RgbImage& image) {
  if (image.width < 1 || image.height < 1 ||
      image.pixels.size() != static_cast<size_t>(image.width) * image.height * 3) {
    return picture_error("PNG: the image is empty or its pixel buffer has the wrong size");
  }
  std::string png;
  const int ok = stbi_write_png_to_func(append_to_string, &png, image.width, image.height, 3, image.pixels.data(),
                                        image.width * 3);
  if (!ok) return picture_error("PNG encoding failed (out of memory?)");
  return png;
}

Result<std::string> matrix_png(const MinMatrixView& matrix, std::span<const int> clip_first_frames,
                               std::span<const Transition> transitions, const MatrixPngSettings& settings) {
  auto image = render_matrix_picture(matrix, clip_first_frames, transitions, settings);
  if (!image) return image.error();
  return encode_png(*image);
}

Result<std::string> matrix_png(std::span<const float> full_matrix, int frame_count,
                               std::span<const int> clip_first_frames, std::span<const Transition> transitions,
                               const MatrixPngSettings& settings) {
  if (Status valid = settings.validate(); !valid) return valid.error();
  if (frame_count < 1) return picture_error("the matrix is empty");
  if (full_matrix.size() != static_cast<size_t>(frame_count) * static_cast<size_t>(frame_count)) {
    return picture_error(
        fmt::format("{} values for a {} x {} matrix", full_matrix.size(), frame_count, frame_count));
  }
  BlockMinMatrix minima(frame_count, settings.max_side_px);
  for (int row = 0; row < frame_count; ++row) {
    minima.add_row(row, 0, full_matrix.subspan(static_cast<size_t>(row) * frame_count, static_cast<size_t>(frame_count)));
  }
  return matrix_png(minima.view(), clip_first_frames, transitions, settings);
}

}  // namespace mg
