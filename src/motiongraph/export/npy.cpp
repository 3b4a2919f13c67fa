// NumPy .npy v1.0 writer: see npy.h for the layout.
#include "motiongraph/export/npy.h"

#include <bit>
#include <cassert>
#include <cstdint>
#include <cstring>

namespace mg {
namespace {

constexpr size_t kNpyAlignment = 64;   // the data offset is a multiple of this (spec: ARRAY_ALIGN)
constexpr size_t kNpyPreamble = 10;   // magic (6) + version (2) + header length (2)
constexpr size_t kNpyMaxDimensions = 32;

// Appends the bytes of `values` in little-endian order, whatever the machine's order.
template <class Float, class Bits>
void append_little_endian(std::string& out, std::span<const Float> values) {
  static_assert(sizeof(Float) == sizeof(Bits));
  const size_t start = out.size();
  out.resize(start + values.size() * sizeof(Float));
  char* dst = out.data() + start;
  if constexpr (std::endian::native == std::endian::little) {
    if (!values.empty()) std::memcpy(dst, values.data(), values.size() * sizeof(Float));
  } else {
    for (const Float value : values) {
      Bits bits = std::bit_cast<Bits>(value);
      for (size_t b = 0; b < sizeof(Bits); ++b) {
        *dst++ = static_cast<char>(bits & 0xFF);
        bits >>= 8;
      }
    }
  }
}

}  // namespace

const char* npy_descr(NpyDtype dtype) { return dtype == NpyDtype::kFloat32 ? "<f4" : "<f8"; }

size_t npy_element_count(std::span<const size_t> shape) {
  size_t count = 1;
  for (const size_t extent : shape) count *= extent;
  return count;
}

std::string npy_header(NpyDtype dtype, std::span<const size_t> shape) {
  assert(shape.size() <= kNpyMaxDimensions);
  // Python tuple syntax: "()", "(5,)", "(3, 4)".
  std::string shape_text = "(";
  for (size_t i = 0; i < shape.size(); ++i) {
    if (i > 0) shape_text += ", ";
    shape_text += std::to_string(shape[i]);
  }
  if (shape.size() == 1) shape_text += ',';
  shape_text += ')';

  std::string dict = std::string("{'descr': '") + npy_descr(dtype) +
                     "', 'fortran_order': False, 'shape': " + shape_text + ", }";
  // Pad with spaces so that preamble + dict + '\n' is a multiple of the alignment.
  const size_t unpadded = kNpyPreamble + dict.size() + 1;
  dict.append((kNpyAlignment - unpadded % kNpyAlignment) % kNpyAlignment, ' ');
  dict += '\n';
  const size_t header_length = dict.size();
  assert(header_length <= 0xFFFF);  // 32 dimensions of 20 digits stay far below

  std::string out = "\x93NUMPY";
  out += '\x01';
  out += '\x00';
  out += static_cast<char>(header_length & 0xFF);
  out += static_cast<char>((header_length >> 8) & 0xFF);
  out += dict;
  assert(out.size() % kNpyAlignment == 0);
  return out;
}

void npy_append_f32(std::string& out, std::span<const float> values) {
  append_little_endian<float, uint32_t>(out, values);
}

void npy_append_f64(std::string& out, std::span<const double> values) {
  append_little_endian<double, uint64_t>(out, values);
}

std::string npy_bytes_f32(std::span<const size_t> shape, std::span<const float> data) {
  assert(data.size() == npy_element_count(shape));
  std::string out = npy_header(NpyDtype::kFloat32, shape);
  out.reserve(out.size() + data.size() * sizeof(float));
  npy_append_f32(out, data);
  return out;
}

std::string npy_bytes_f64(std::span<const size_t> shape, std::span<const double> data) {
  assert(data.size() == npy_element_count(shape));
  std::string out = npy_header(NpyDtype::kFloat64, shape);
  out.reserve(out.size() + data.size() * sizeof(double));
  npy_append_f64(out, data);
  return out;
}

}  // namespace mg
