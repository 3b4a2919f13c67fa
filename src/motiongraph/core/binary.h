// Little-endian binary serialisation for the project's own files (graph and cache files):
// a writer that appends values to a byte string, and a reader that checks every read against
// the end of the data and reports truncation as an error instead of reading past it.
#pragma once

#include <bit>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "motiongraph/core/error.h"
#include "motiongraph/core/huge_pages.h"

namespace mg {

static_assert(std::endian::native == std::endian::little, "motiongraph files are little-endian");

class BinaryWriter {
 public:
  template <class T>
  void put(const T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    const auto* bytes = reinterpret_cast<const char*>(&value);
    data_.append(bytes, sizeof(T));
  }
  void put_string(std::string_view s) {
    put<std::uint64_t>(s.size());
    data_.append(s.data(), s.size());
  }
  template <class T>
  void put_vector(const std::vector<T>& values) {
    static_assert(std::is_trivially_copyable_v<T>);
    put<std::uint64_t>(values.size());
    data_.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
  }
  const std::string& data() const { return data_; }
  std::string take() { return std::move(data_); }

 private:
  std::string data_;
};

class BinaryReader {
 public:
  BinaryReader(std::string_view data, std::string file_name) : data_(data), file_(std::move(file_name)) {}

  template <class T>
  bool get(T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    if (data_.size() - pos_ < sizeof(T)) return fail();
    std::memcpy(&value, data_.data() + pos_, sizeof(T));
    pos_ += sizeof(T);
    return true;
  }
  bool get_string(std::string& s) {
    std::uint64_t size = 0;
    if (!get(size) || size > data_.size() - pos_) return fail();
    s.assign(data_.data() + pos_, size);
    pos_ += size;
    return true;
  }
  template <class T>
  bool get_vector(std::vector<T>& values) {
    std::uint64_t size = 0;
    if (!get(size) || size > (data_.size() - pos_) / sizeof(T)) return fail();
    // Large vectors (a whole library's candidate minima: 160 MB) into huge pages.
    if (values.empty() && size * sizeof(T) >= 4 * kHugePageBytes) reserve_huge(values, size);
    values.resize(size);
    // An empty vector's data() may be null, which memcpy must not be given even for 0 bytes.
    if (size > 0) std::memcpy(values.data(), data_.data() + pos_, size * sizeof(T));
    pos_ += size * sizeof(T);
    return true;
  }
  // A vector put_vector wrote, in place: its size and its bytes (not aligned for T: read its
  // values with std::memcpy).
  template <class T>
  bool view_vector(std::uint64_t& size, const char*& bytes) {
    if (!get(size) || size > (data_.size() - pos_) / sizeof(T)) return fail();
    bytes = data_.data() + pos_;
    pos_ += size * sizeof(T);
    return true;
  }
  bool ok() const { return ok_; }
  bool at_end() const { return pos_ == data_.size(); }
  size_t position() const { return pos_; }
  Error error(std::string message) const { return Error{file_, 0, std::move(message)}; }

 private:
  bool fail() {
    ok_ = false;
    return false;
  }
  std::string_view data_;
  std::string file_;
  size_t pos_ = 0;
  bool ok_ = true;
};

}  // namespace mg
