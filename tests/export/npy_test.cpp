// NumPy .npy writer: the header read back per the format spec, data bytes bit for bit, the
// streaming form equal to the whole-array form, and (when numpy is installed) numpy itself.
#include "motiongraph/export/npy.h"

#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <limits>
#include <random>
#include <regex>
#include <vector>

#include "motiongraph/io/file.h"

namespace mg {
namespace {

struct ParsedNpy {
  int major = 0;
  int minor = 0;
  size_t data_offset = 0;
  std::string descr;
  std::string fortran_order;
  std::string shape_text;         // inside the parentheses, as written
  std::vector<size_t> shape;
};

// Reads the preamble and the header dict as the spec describes them; fails the test on any
// departure from it.
ParsedNpy parse_npy(const std::string& bytes) {
  ParsedNpy parsed;
  EXPECT_GE(bytes.size(), 10u);
  if (bytes.size() < 10) return parsed;
  EXPECT_EQ(bytes.substr(0, 6), std::string("\x93NUMPY"));
  parsed.major = static_cast<unsigned char>(bytes[6]);
  parsed.minor = static_cast<unsigned char>(bytes[7]);
  const size_t header_length =
      static_cast<unsigned char>(bytes[8]) | (static_cast<size_t>(static_cast<unsigned char>(bytes[9])) << 8);
  parsed.data_offset = 10 + header_length;
  EXPECT_LE(parsed.data_offset, bytes.size());
  if (parsed.data_offset > bytes.size()) return parsed;
  const std::string header = bytes.substr(10, header_length);
  EXPECT_EQ(header.back(), '\n') << "the header ends with a newline";
  for (const char c : header) EXPECT_TRUE(c >= 0x20 || c == '\n') << "header is printable ASCII";

  static const std::regex kDict(
      R"(^\{'descr': '([^']*)', 'fortran_order': (True|False), 'shape': \(([^)]*)\), \} *\n$)");
  std::smatch match;
  EXPECT_TRUE(std::regex_match(header, match, kDict)) << "header: " << header;
  if (match.empty()) return parsed;
  parsed.descr = match[1];
  parsed.fortran_order = match[2];
  parsed.shape_text = match[3];
  static const std::regex kExtent(R"((\d+),?)");
  for (auto it = std::sregex_iterator(parsed.shape_text.begin(), parsed.shape_text.end(), kExtent);
       it != std::sregex_iterator(); ++it) {
    parsed.shape.push_back(std::stoull((*it)[1]));
  }
  return parsed;
}

template <class T>
std::vector<T> data_of(const std::string& bytes, size_t offset) {
  std::vector<T> values((bytes.size() - offset) / sizeof(T));
  std::memcpy(values.data(), bytes.data() + offset, values.size() * sizeof(T));
  return values;
}

TEST(Npy, OneDimensionalFloat32HeaderFollowsTheSpec) {
  const std::array<size_t, 1> shape = {5};
  const std::vector<float> data = {1.0f, -2.5f, 0.0f, 3.25e-7f, 1e30f};
  const std::string bytes = npy_bytes_f32(shape, data);
  const ParsedNpy parsed = parse_npy(bytes);
  EXPECT_EQ(parsed.major, 1);
  EXPECT_EQ(parsed.minor, 0);
  EXPECT_EQ(parsed.descr, "<f4");
  EXPECT_EQ(parsed.fortran_order, "False");
  EXPECT_EQ(parsed.shape_text, "5,") << "a 1-d shape is the tuple (5,)";
  EXPECT_EQ(parsed.data_offset % 64, 0u);
  EXPECT_EQ(bytes.size(), parsed.data_offset + data.size() * 4);
  EXPECT_EQ(data_of<float>(bytes, parsed.data_offset), data);
}

TEST(Npy, ShapesOfEveryRankAreWrittenAsPythonTuples) {
  const std::vector<float> one = {4.0f};
  EXPECT_EQ(parse_npy(npy_bytes_f32({}, one)).shape_text, "");  // 0-d: ()
  const std::array<size_t, 2> matrix = {3, 4};
  const std::vector<float> twelve(12, 1.0f);
  EXPECT_EQ(parse_npy(npy_bytes_f32(matrix, twelve)).shape_text, "3, 4");
  const std::array<size_t, 3> cloud = {2, 31, 3};
  const std::vector<double> values(2 * 31 * 3, 0.5);
  const ParsedNpy parsed = parse_npy(npy_bytes_f64(cloud, values));
  EXPECT_EQ(parsed.shape_text, "2, 31, 3");
  EXPECT_EQ(parsed.shape, (std::vector<size_t>{2, 31, 3}));
  EXPECT_EQ(parsed.descr, "<f8");
  const std::array<size_t, 2> empty = {0, 7};
  EXPECT_EQ(parse_npy(npy_bytes_f64(empty, {})).shape_text, "0, 7");
}

TEST(Npy, DataStartsAtAMultipleOf64ForAnyShape) {
  std::mt19937 random(7);
  for (size_t rank = 0; rank <= 32; ++rank) {
    std::vector<size_t> shape(rank);
    for (auto& extent : shape) extent = random() % 2 == 0 ? 1 : 1000000007ull;  // short and long numbers
    for (const NpyDtype dtype : {NpyDtype::kFloat32, NpyDtype::kFloat64}) {
      const std::string header = npy_header(dtype, shape);
      EXPECT_EQ(header.size() % 64, 0u) << "rank " << rank;
      const ParsedNpy parsed = parse_npy(header);
      EXPECT_EQ(parsed.data_offset, header.size());
      EXPECT_EQ(parsed.shape, shape);
    }
  }
}

TEST(Npy, NanInfinityAndSignedZeroSurviveBitForBit) {
  const std::vector<float> f32 = {std::numeric_limits<float>::quiet_NaN(), std::bit_cast<float>(0x7FC01234u),
                                  std::bit_cast<float>(0xFFC00001u), -0.0f, std::numeric_limits<float>::infinity(),
                                  -std::numeric_limits<float>::infinity(), std::numeric_limits<float>::denorm_min()};
  const std::array<size_t, 1> shape32 = {f32.size()};
  const std::string bytes32 = npy_bytes_f32(shape32, f32);
  const size_t offset32 = parse_npy(bytes32).data_offset;
  ASSERT_EQ(bytes32.size() - offset32, f32.size() * 4);
  EXPECT_EQ(std::memcmp(bytes32.data() + offset32, f32.data(), f32.size() * 4), 0);

  const std::vector<double> f64 = {std::numeric_limits<double>::quiet_NaN(),
                                   std::bit_cast<double>(0x7FF8000000ABCDEFull), -0.0,
                                   std::numeric_limits<double>::infinity()};
  const std::array<size_t, 2> shape64 = {2, 2};
  const std::string bytes64 = npy_bytes_f64(shape64, f64);
  const size_t offset64 = parse_npy(bytes64).data_offset;
  ASSERT_EQ(bytes64.size() - offset64, f64.size() * 8);
  EXPECT_EQ(std::memcmp(bytes64.data() + offset64, f64.data(), f64.size() * 8), 0);
}

TEST(Npy, DataIsLittleEndian) {
  const std::vector<float> one = {1.0f};  // 0x3F800000
  const std::array<size_t, 1> shape = {1};
  const std::string bytes = npy_bytes_f32(shape, one);
  EXPECT_EQ(bytes.substr(bytes.size() - 4), std::string("\x00\x00\x80\x3F", 4));
  const std::vector<double> two = {2.0};  // 0x4000000000000000
  const std::string bytes64 = npy_bytes_f64(shape, two);
  EXPECT_EQ(bytes64.substr(bytes64.size() - 8), std::string("\x00\x00\x00\x00\x00\x00\x00\x40", 8));
}

TEST(Npy, StreamingRowsEqualsTheWholeArray) {
  const size_t rows = 7;
  const size_t cols = 13;
  std::vector<float> matrix(rows * cols);
  for (size_t i = 0; i < matrix.size(); ++i) matrix[i] = static_cast<float>(i) * 0.37f - 5.0f;
  matrix[20] = std::numeric_limits<float>::quiet_NaN();
  const std::array<size_t, 2> shape = {rows, cols};

  std::string streamed = npy_header(NpyDtype::kFloat32, shape);
  for (size_t r = 0; r < rows; ++r) npy_append_f32(streamed, std::span(matrix).subspan(r * cols, cols));
  EXPECT_EQ(streamed, npy_bytes_f32(shape, matrix));

  std::vector<double> matrix64(matrix.begin(), matrix.end());
  std::string streamed64 = npy_header(NpyDtype::kFloat64, shape);
  for (size_t r = 0; r < rows; ++r) npy_append_f64(streamed64, std::span(matrix64).subspan(r * cols, cols));
  EXPECT_EQ(streamed64, npy_bytes_f64(shape, matrix64));
}

// The first python3 that imports numpy, or "" (python3 on PATH, then the system's).
std::string python_with_numpy() {
  for (const char* python : {"python3", "/usr/bin/python3"}) {
    const std::string command = std::string(python) + " -c 'import numpy' >/dev/null 2>&1";
    if (std::system(command.c_str()) == 0) return python;
  }
  return "";
}

std::string run_and_read(const std::string& command) {
  std::string output;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return output;
  char buffer[4096];
  size_t n;
  while ((n = fread(buffer, 1, sizeof(buffer), pipe)) > 0) output.append(buffer, n);
  const int status = pclose(pipe);
  if (status != 0) output += "\n[exit status " + std::to_string(status) + "]";
  return output;
}

std::string hex_of(const void* data, size_t size) {
  static const char* kDigits = "0123456789abcdef";
  std::string hex;
  const auto* bytes = static_cast<const unsigned char*>(data);
  for (size_t i = 0; i < size; ++i) {
    hex += kDigits[bytes[i] >> 4];
    hex += kDigits[bytes[i] & 15];
  }
  return hex;
}

TEST(Npy, NumpyLoadsWhatWeWrite) {
  const std::string python = python_with_numpy();
  if (python.empty()) GTEST_SKIP() << "numpy is not installed (python3 -c 'import numpy' fails): skipped";

  const auto folder = std::filesystem::temp_directory_path() /
                      ("motiongraph_npy_test_" + std::to_string(std::random_device{}()));
  std::filesystem::create_directories(folder);

  std::vector<float> matrix(3 * 4);
  for (size_t i = 0; i < matrix.size(); ++i) matrix[i] = static_cast<float>(i) * 0.25f - 1.0f;
  matrix[6] = std::numeric_limits<float>::quiet_NaN();
  const std::array<size_t, 2> matrix_shape = {3, 4};
  const std::vector<double> vector = {0.1, -0.0, 1e300, std::numeric_limits<double>::quiet_NaN(), 42.0};
  const std::array<size_t, 1> vector_shape = {5};

  const std::string f32_path = (folder / "matrix.npy").string();
  const std::string f64_path = (folder / "vector.npy").string();
  const std::string script_path = (folder / "check.py").string();
  ASSERT_TRUE(write_file_atomic(f32_path, npy_bytes_f32(matrix_shape, matrix)));
  ASSERT_TRUE(write_file_atomic(f64_path, npy_bytes_f64(vector_shape, vector)));
  ASSERT_TRUE(write_file_atomic(script_path,
                                "import sys\n"
                                "import numpy as np\n"
                                "for path, descr in zip(sys.argv[1:], ['<f4', '<f8']):\n"
                                "    a = np.load(path, allow_pickle=False)\n"
                                "    print(a.dtype.newbyteorder('<').str == descr, a.shape, a.flags.c_contiguous)\n"
                                "    print(a.astype(descr).tobytes().hex())\n"
                                "    print(repr(a.ravel().tolist()))\n"));

  const std::string output = run_and_read(python + " " + script_path + " " + f32_path + " " + f64_path);
  const std::string expected = "True (3, 4) True\n" + hex_of(matrix.data(), matrix.size() * 4) + "\n" +
                               "[-1.0, -0.75, -0.5, -0.25, 0.0, 0.25, nan, 0.75, 1.0, 1.25, 1.5, 1.75]\n" +
                               "True (5,) True\n" + hex_of(vector.data(), vector.size() * 8) + "\n" +
                               "[0.1, -0.0, 1e+300, nan, 42.0]\n";
  EXPECT_EQ(output, expected);
  std::error_code ignored;
  std::filesystem::remove_all(folder, ignored);
}

}  // namespace
}  // namespace mg
