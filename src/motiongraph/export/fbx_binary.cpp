#include "motiongraph/export/fbx_binary.h"

#include <cstring>
#include <limits>
#include <type_traits>

#include <fmt/format.h>
#include <zlib.h>

namespace mg {

namespace {

constexpr char kMagic[] = "Kaydara FBX Binary  \0\x1a";  // with its terminating '\0': 23 bytes
constexpr unsigned char kFooterId[16] = {0xfa, 0xbc, 0xab, 0x09, 0xd0, 0xc8, 0xd4, 0x66,
                                         0xb1, 0x76, 0xfb, 0x83, 0x1c, 0xf7, 0x26, 0x7e};
constexpr unsigned char kFooterMagic[16] = {0xf8, 0x5a, 0x8c, 0x6a, 0xde, 0xf5, 0xd9, 0x7e,
                                            0xec, 0xe9, 0x0c, 0xe3, 0x75, 0x8f, 0x29, 0x0b};
constexpr size_t kNullRecord = 13;     // 7.4: three uint32 and a name length, all zero
constexpr size_t kCompressFrom = 128;  // arrays of this many bytes or more are deflated (as Blender does)

class Encoder {
 public:
  template <class T>
  void put(const T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    out_.append(reinterpret_cast<const char*>(&value), sizeof(T));
  }
  void bytes(const void* data, size_t size) {
    if (size > 0) out_.append(static_cast<const char*>(data), size);  // an empty vector's data() may be null
  }
  void zeros(size_t count) { out_.append(count, '\0'); }
  size_t size() const { return out_.size(); }
  void patch_u32(size_t at, std::uint32_t value) { std::memcpy(out_.data() + at, &value, sizeof value); }
  std::string take() { return std::move(out_); }

  // A length-prefixed string or raw value ('S', 'R').
  void counted(char type, const std::string& text) {
    put(type);
    put(static_cast<std::uint32_t>(text.size()));
    bytes(text.data(), text.size());
  }

  // An array value: count, encoding (0: as it is, 1: zlib's deflate, when long and smaller so),
  // byte length, the bytes.
  template <class T>
  void array(char type, const std::vector<T>& values) {
    const size_t size = values.size() * sizeof(T);
    put(type);
    put(static_cast<std::uint32_t>(values.size()));
    if (size >= kCompressFrom && size <= std::numeric_limits<uLong>::max()) {
      uLongf packed_size = compressBound(static_cast<uLong>(size));
      std::string packed(packed_size, '\0');
      if (compress2(reinterpret_cast<Bytef*>(packed.data()), &packed_size,
                    reinterpret_cast<const Bytef*>(values.data()), static_cast<uLong>(size), Z_BEST_SPEED) == Z_OK &&
          packed_size < size) {
        put(std::uint32_t{1});
        put(static_cast<std::uint32_t>(packed_size));
        bytes(packed.data(), packed_size);
        return;
      }
    }
    put(std::uint32_t{0});
    put(static_cast<std::uint32_t>(size));
    bytes(values.data(), size);
  }

  void value(const FbxValue& v) {
    std::visit(
        [this](const auto& x) {
          using T = std::decay_t<decltype(x)>;
          if constexpr (std::is_same_v<T, std::int32_t>) {
            put('I'), put(x);
          } else if constexpr (std::is_same_v<T, std::int64_t>) {
            put('L'), put(x);
          } else if constexpr (std::is_same_v<T, float>) {
            put('F'), put(x);
          } else if constexpr (std::is_same_v<T, double>) {
            put('D'), put(x);
          } else if constexpr (std::is_same_v<T, std::string>) {
            counted('S', x);
          } else if constexpr (std::is_same_v<T, FbxRaw>) {
            counted('R', x.bytes);
          } else if constexpr (std::is_same_v<T, std::vector<std::int32_t>>) {
            array('i', x);
          } else if constexpr (std::is_same_v<T, std::vector<std::int64_t>>) {
            array('l', x);
          } else if constexpr (std::is_same_v<T, std::vector<float>>) {
            array('f', x);
          } else {
            static_assert(std::is_same_v<T, std::vector<double>>);
            array('d', x);
          }
        },
        v);
  }

  Status record(const FbxRecord& r) {
    if (r.name.size() > 255)
      return Error{"", 0, fmt::format("FBX record name '{}...' is over 255 bytes", r.name.substr(0, 40))};
    const size_t start = size();
    put(std::uint32_t{0});  // the end's offset, patched below
    put(static_cast<std::uint32_t>(r.values.size()));
    put(std::uint32_t{0});  // the values' byte length, patched below
    put(static_cast<std::uint8_t>(r.name.size()));
    bytes(r.name.data(), r.name.size());
    const size_t values_start = size();
    for (const FbxValue& v : r.values) value(v);
    if (size() > std::numeric_limits<std::uint32_t>::max()) return too_large();
    patch_u32(start + 8, static_cast<std::uint32_t>(size() - values_start));
    for (const FbxRecord& inner : r.records) {
      if (auto s = record(inner); !s) return s;
    }
    if (!r.records.empty() || r.block) zeros(kNullRecord);
    if (size() > std::numeric_limits<std::uint32_t>::max()) return too_large();
    patch_u32(start, static_cast<std::uint32_t>(size()));
    return Ok{};
  }

  static Error too_large() {
    return Error{"", 0, "the FBX file would be over 4 GB, FBX 7.4's limit: write fewer frames"};
  }

 private:
  std::string out_;
};

}  // namespace

Result<std::string> encode_fbx_binary(std::span<const FbxRecord> top) {
  Encoder out;
  out.bytes(kMagic, sizeof kMagic);
  out.put(kFbxBinaryVersion);
  for (const FbxRecord& r : top) {
    if (auto s = out.record(r); !s) return s.error();
  }
  out.zeros(kNullRecord);
  // The footer as Blender's and the FBX SDK's files end: its id, 4 zeros, zeros to the next
  // 16-byte boundary (at least one), the version there, 120 zeros, the closing magic.
  out.bytes(kFooterId, sizeof kFooterId);
  out.zeros(4);
  out.zeros(16 - out.size() % 16);
  out.put(kFbxBinaryVersion);
  out.zeros(120);
  out.bytes(kFooterMagic, sizeof kFooterMagic);
  return out.take();
}

}  // namespace mg
