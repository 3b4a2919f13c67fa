#include "export/fbx_binary_reader.h"

#include <cstdint>
#include <cstring>
#include <optional>

#include <fmt/format.h>
#include <zlib.h>

namespace mg::test {

namespace {

class Reader {
 public:
  explicit Reader(std::string_view bytes) : bytes_(bytes) {}

  template <class T>
  bool get(T& value) {
    if (bytes_.size() - pos_ < sizeof(T)) return false;
    std::memcpy(&value, bytes_.data() + pos_, sizeof(T));
    pos_ += sizeof(T);
    return true;
  }
  bool get_bytes(size_t count, std::string& out) {
    if (bytes_.size() - pos_ < count) return false;
    out.assign(bytes_.data() + pos_, count);
    pos_ += count;
    return true;
  }
  size_t pos() const { return pos_; }
  int deflated() const { return deflated_; }
  size_t size() const { return bytes_.size(); }
  Error error(const std::string& what) const { return Error{"fbx", static_cast<int>(pos_), what}; }

  template <class T>
  Result<FbxValue> array() {
    std::uint32_t count = 0, encoding = 0, length = 0;
    if (!get(count) || !get(encoding) || !get(length)) return error("array header cut short");
    if (encoding > 1) return error(fmt::format("array encoding {}", encoding));
    if (encoding == 0 && length != count * sizeof(T)) return error("array byte length is not its count's");
    std::vector<T> values(count);
    std::string raw;
    if (!get_bytes(length, raw)) return error("array cut short");
    if (encoding == 0) {
      if (length > 0) std::memcpy(values.data(), raw.data(), length);
    } else {
      uLongf size = count * sizeof(T);
      if (uncompress(reinterpret_cast<Bytef*>(values.data()), &size, reinterpret_cast<const Bytef*>(raw.data()),
                     length) != Z_OK ||
          size != count * sizeof(T)) {
        return error("deflated array does not inflate to its count");
      }
      ++deflated_;
    }
    return FbxValue(std::move(values));
  }

  Result<FbxValue> value() {
    char type = 0;
    if (!get(type)) return error("value cut short");
    switch (type) {
      case 'I': {
        std::int32_t v;
        if (get(v)) return FbxValue(v);
        break;
      }
      case 'L': {
        std::int64_t v;
        if (get(v)) return FbxValue(v);
        break;
      }
      case 'F': {
        float v;
        if (get(v)) return FbxValue(v);
        break;
      }
      case 'D': {
        double v;
        if (get(v)) return FbxValue(v);
        break;
      }
      case 'S':
      case 'R': {
        std::uint32_t length = 0;
        std::string text;
        if (!get(length) || !get_bytes(length, text)) break;
        if (type == 'S') return FbxValue(text);
        return FbxValue(FbxRaw{text});
      }
      case 'i':
        return array<std::int32_t>();
      case 'l':
        return array<std::int64_t>();
      case 'f':
        return array<float>();
      case 'd':
        return array<double>();
      default:
        return error(fmt::format("value type '{}'", type));
    }
    return error("value cut short");
  }

  // A record, or nullopt at a null record (which ends a list).
  Result<std::optional<FbxRecord>> record() {
    const size_t start = pos_;
    std::uint32_t end = 0, count = 0, length = 0;
    std::uint8_t name_length = 0;
    if (!get(end) || !get(count) || !get(length) || !get(name_length)) return error("record header cut short");
    if (end == 0 && count == 0 && length == 0 && name_length == 0) return std::optional<FbxRecord>();
    FbxRecord r;
    if (!get_bytes(name_length, r.name)) return error("record name cut short");
    const size_t values_start = pos_;
    for (std::uint32_t i = 0; i < count; ++i) {
      auto v = value();
      if (!v) return v.error();
      r.values.push_back(std::move(*v));
    }
    if (pos_ - values_start != length)
      return error(fmt::format("record '{}': values' length {} is not {}", r.name, length, pos_ - values_start));
    if (end < pos_ || end > bytes_.size())
      return error(fmt::format("record '{}' (at {}): end {} out of place", r.name, start, end));
    if (pos_ < end) {  // records inside, then a null record
      for (;;) {
        auto inner = record();
        if (!inner) return inner.error();
        if (!*inner) break;
        r.records.push_back(std::move(**inner));
      }
      r.block = r.records.empty();
    }
    if (pos_ != end) return error(fmt::format("record '{}' (at {}) ends at {}, says {}", r.name, start, pos_, end));
    return std::optional<FbxRecord>(std::move(r));
  }

 private:
  std::string_view bytes_;
  size_t pos_ = 0;
  int deflated_ = 0;
};

}  // namespace

Result<std::vector<FbxRecord>> read_fbx_binary(std::string_view bytes, int* deflated_arrays) {
  Reader in(bytes);
  std::string magic;
  std::uint32_t version = 0;
  if (!in.get_bytes(23, magic) || magic != std::string("Kaydara FBX Binary  \0\x1a\0", 23))
    return in.error("not FBX's magic");
  if (!in.get(version) || version != 7400) return in.error("not version 7400");
  std::vector<FbxRecord> top;
  for (;;) {
    auto r = in.record();
    if (!r) return r.error();
    if (!*r) break;
    top.push_back(std::move(**r));
  }
  // The footer: id, then zeros so that the version starts on a 16-byte boundary, 120 zeros, magic.
  std::string rest;
  if (!in.get_bytes(in.size() - in.pos(), rest)) return in.error("footer");
  const std::string id("\xfa\xbc\xab\x09\xd0\xc8\xd4\x66\xb1\x76\xfb\x83\x1c\xf7\x26\x7e", 16);
  const std::string end_magic("\xf8\x5a\x8c\x6a\xde\xf5\xd9\x7e\xec\xe9\x0c\xe3\x75\x8f\x29\x0b", 16);
  const size_t footer = bytes.size() - rest.size();
  const size_t version_at = bytes.size() - 16 - 120 - 4;
  if (rest.compare(0, 16, id) != 0) return Error{"fbx", static_cast<int>(footer), "footer id"};
  if (version_at % 16 != 0 || version_at < footer + 16 + 5 || version_at > footer + 16 + 20) {
    return Error{"fbx", static_cast<int>(version_at),
                 "footer version not on the 16-byte boundary after the id and 4 zeros"};
  }
  for (size_t i = footer + 16; i < version_at; ++i) {
    if (bytes[i] != '\0') return Error{"fbx", static_cast<int>(i), "footer padding not zero"};
  }
  std::uint32_t footer_version = 0;
  std::memcpy(&footer_version, bytes.data() + version_at, 4);
  if (footer_version != 7400) return Error{"fbx", static_cast<int>(version_at), "footer version"};
  for (size_t i = version_at + 4; i < version_at + 124; ++i) {
    if (bytes[i] != '\0') return Error{"fbx", static_cast<int>(i), "footer zeros"};
  }
  if (bytes.substr(bytes.size() - 16) != end_magic)
    return Error{"fbx", static_cast<int>(bytes.size() - 16), "footer magic"};
  if (deflated_arrays) *deflated_arrays = in.deflated();
  return top;
}

const FbxRecord* find_record(const std::vector<FbxRecord>& records, const std::string& name) {
  for (const FbxRecord& r : records) {
    if (r.name == name) return &r;
  }
  return nullptr;
}

}  // namespace mg::test
