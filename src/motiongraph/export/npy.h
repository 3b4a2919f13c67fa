// NumPy .npy serialisation (format version 1.0) of an N-dimensional float32 or float64 array,
// in memory: the caller writes the bytes with write_file_atomic (io/file.h).
//
// Layout, per the NumPy format spec (numpy.lib.format):
//   "\x93NUMPY" | major 1 | minor 0 | header length (uint16, little-endian) | header | data
// The header is a Python dict literal, e.g. "{'descr': '<f4', 'fortran_order': False,
// 'shape': (5,), }", padded with spaces and ended by '\n' so that the data starts at a
// multiple of 64 bytes. Data: little-endian IEEE 754 (`<f4` / `<f8`), C order (last index
// fastest), bit for bit: NaN payloads and signed zeros survive.
//
// Arrays too large to hold twice are streamed: npy_header() for the shape, then each row's
// bytes through npy_append_f32/f64, which convert exactly as the whole-array functions do.
#pragma once

#include <cstddef>
#include <span>
#include <string>

namespace mg {

enum class NpyDtype { kFloat32, kFloat64 };

// "<f4" or "<f8".
const char* npy_descr(NpyDtype dtype);

// Number of elements of an array of this shape (1 for a 0-d array, shape {}).
size_t npy_element_count(std::span<const size_t> shape);

// Magic, version, header length and padded header: everything before the data. Its size is a
// multiple of 64. At most 32 dimensions (NumPy's own limit), so the header always fits v1.0.
std::string npy_header(NpyDtype dtype, std::span<const size_t> shape);

// Appends `values` to `out` as little-endian data bytes (4 or 8 bytes per value).
void npy_append_f32(std::string& out, std::span<const float> values);
void npy_append_f64(std::string& out, std::span<const double> values);

// The whole file: header then data. data.size() must equal npy_element_count(shape).
std::string npy_bytes_f32(std::span<const size_t> shape, std::span<const float> data);
std::string npy_bytes_f64(std::span<const size_t> shape, std::span<const double> data);

}  // namespace mg
