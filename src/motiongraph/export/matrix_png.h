// The distance-matrix picture (Kovar et al. 2002, figure 2) as PNG bytes, in memory: the
// caller writes them with write_file_atomic (io/file.h).
//
// Matrix: square, N x N global frames, row-major; row = the frame we leave, column = the
// frame we arrive at; NaN = undefined (e.g. a window that crosses a clip end). Image: pixel
// (x, y) shows column x, row y, so the picture reads like the matrix.
//
// Large N: the picture is at most max_side_px pixels a side. Each pixel is the MINIMUM over
// a block x block square of entries (block = ceil(N / max_side_px)), so local minima, the
// transition candidates, stay visible. The full N x N matrix need not exist: the distance
// stage folds entries into a BlockMinMatrix as it computes them, and the picture is drawn
// from that (the full-matrix overload does exactly the same, in one call).
//
// Colours: finite values from the smallest (dark purple) to the high_percentile-th
// percentile of the finite pixel values (yellow, everything above clamps there) on the
// viridis ramp (perceptually uniform, lightness rising with the value); undefined pixels are
// mid grey, +infinity (above the pruned distance stage's ceiling) light grey; clip starts are thin lines blended halfway toward white; transitions are small
// red "+" crosses. Fails (as a value) on invalid settings, inconsistent shapes, or frame
// indices outside the matrix.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "motiongraph/core/error.h"
#include "motiongraph/graph/transition.h"

namespace mg {

using Rgb = std::array<std::uint8_t, 3>;

inline constexpr Rgb kMatrixUndefinedRgb = {128, 128, 128};
// +infinity: a block whose pairs all lie above the pruned distance stage's ceiling (not
// computed; pruned_candidates.h). Light grey, apart from the undefined and the ramp.
inline constexpr Rgb kMatrixAboveCeilingRgb = {208, 208, 208};
inline constexpr Rgb kMatrixTransitionRgb = {255, 0, 0};
inline constexpr Rgb kMatrixBoundaryRgb = {255, 255, 255};  // blended 50% over the pixel

struct MatrixPngSettings {
  int max_side_px = 1024;         // the image is at most this many pixels a side
  double high_percentile = 99.0;  // finite values at or above it get the lightest colour
  int marker_radius_px = 2;       // arm length of a transition's cross (0: a single pixel)

  Status validate() const;
};

// Frames per pixel so that ceil(frame_count / block) <= max_side_px (at least 1).
int min_matrix_block(int frame_count, int max_side_px);

// A downsampled matrix of block minima: side x side, row-major; pixel (i, j) holds the minimum
// over rows [i*block, (i+1)*block) and columns [j*block, (j+1)*block) of the full matrix
// (the last block may be partial); NaN where every entry of its block is undefined.
struct MinMatrixView {
  std::span<const float> values;
  int side = 0;   // M
  int block = 1;  // the scale factor: frames per pixel along each axis
};

// Block minima held by value (what coarsen_min_matrix returns).
struct MinMatrix {
  std::vector<float> values;
  int side = 0;
  int block = 1;

  MinMatrixView view() const { return {values, side, block}; }
};

// The block minima of the same full frame_count x frame_count matrix at a block that is the
// smallest multiple of matrix.block giving at most max_side_px pixels a side: exact, since each
// new block is a union of old ones (the picture a graph file stores, made smaller to serve).
// The matrix as it is when it is small enough already.
MinMatrix coarsen_min_matrix(const MinMatrixView& matrix, int frame_count, int max_side_px);

// Folds full-matrix entries into their block minima. Start state: all undefined (NaN).
// Not thread-safe: give each thread its own (then merge()), or split the work by block rows
// (rows [i*block, (i+1)*block) all to one thread), so no two threads touch the same pixel.
class BlockMinMatrix {
 public:
  BlockMinMatrix(int frame_count, int max_side_px);

  int frame_count() const { return frame_count_; }
  int block() const { return block_; }
  int side() const { return side_; }

  // Entry (row, col) of the full matrix; NaN values never replace a finite minimum.
  void add(int row, int col, float value) {
    float& cell = values_[static_cast<size_t>(row / block_) * side_ + col / block_];
    if (value < cell || std::isnan(cell)) cell = value;
  }
  // Entries (row, first_col), (row, first_col + 1), ... of the full matrix.
  void add_row(int row, int first_col, std::span<const float> values);
  // Takes the minimum with another accumulator of the same frame_count and block.
  void merge(const BlockMinMatrix& other);

  std::span<const float> values() const { return values_; }
  MinMatrixView view() const { return {values_, side_, block_}; }

 private:
  int frame_count_ = 0;
  int block_ = 1;
  int side_ = 0;
  std::vector<float> values_;
};

// An 8-bit RGB raster, row-major, 3 bytes a pixel, no padding.
struct RgbImage {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> pixels;

  Rgb at(int x, int y) const;
};

// The ramp: t in [0, 1] (clamped) from dark to light.
Rgb matrix_ramp(double t);

// The picture as pixels (side x side of the min-matrix; side must be <= max_side_px).
// clip_first_frames: global first frame of each clip (frame 0 draws no line);
// transitions: from_frame is the row, to_frame the column.
Result<RgbImage> render_matrix_picture(const MinMatrixView& matrix, std::span<const int> clip_first_frames,
                                       std::span<const Transition> transitions,
                                       const MatrixPngSettings& settings);

// PNG bytes of an image (stb_image_write, 8-bit RGB).
Result<std::string> encode_png(const RgbImage& image);

// render_matrix_picture + encode_png, from block minima.
Result<std::string> matrix_png(const MinMatrixView& matrix, std::span<const int> clip_first_frames,
                               std::span<const Transition> transitions, const MatrixPngSettings& settings);

// The same from the full frame_count x frame_count matrix (row-major), downsampled here.
Result<std::string> matrix_png(std::span<const float> full_matrix, int frame_count,
                               std::span<const int> clip_first_frames, std::span<const Transition> transitions,
                               const MatrixPngSettings& settings);

}  // namespace mg
