// FBX's binary encoding (version 7.4, as Blender, Maya and the FBX SDK of 2014-2019 write it) of
// a tree of records: each record a name, a list of typed values and the records inside it, as an
// ASCII FBX file shows them ("Model: 123, "Hips\0\1Model", "LimbNode" { Version: 232 ... }").
//
// The layout (public since Blender's 2013 write-up of the format): the 23-byte magic
// "Kaydara FBX Binary  \0\x1a\0" and the version; each record as its end's offset in the file,
// its value count, its values' byte length, its name's length and name, its values (a type
// letter each: I int32, L int64, F float, D double, S string, R raw bytes, and arrays i l f d as
// count, encoding (0 plain; 1 zlib-deflated, which arrays of 128 bytes or more get when it makes
// them smaller, as Blender's and the FBX SDK's files have them), byte length, bytes), its records, and a 13-byte null
// record ending the list of records inside it; a null record after the last top record; then the footer the FBX SDK
// checks: a fixed 16-byte id, zeros to a 16-byte boundary, the version, 120 zeros and a fixed 16-byte magic. The
// footer's id goes with the file id and creation time the file's header records carry (kFbxFileId, kFbxCreationTime:
// the FBX SDK checks them together; every writer without the SDK uses these three). Little-endian throughout.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "motiongraph/core/error.h"

namespace mg {

struct FbxRaw {  // an 'R' value: bytes, not text
  std::string bytes;
  friend bool operator==(const FbxRaw&, const FbxRaw&) = default;
};

using FbxValue = std::variant<std::int32_t, std::int64_t, float, double, std::string, FbxRaw, std::vector<std::int32_t>,
                              std::vector<std::int64_t>, std::vector<float>, std::vector<double>>;

struct FbxRecord {
  std::string name;
  std::vector<FbxValue> values;
  std::vector<FbxRecord> records;
  bool block = false;  // written as a block ({ }) even without records inside, as FBX writes an
                       // AnimationLayer or References

  FbxRecord& add(FbxRecord record) { return records.emplace_back(std::move(record)); }
  friend bool operator==(const FbxRecord&, const FbxRecord&) = default;
};

inline constexpr std::uint32_t kFbxBinaryVersion = 7400;
inline constexpr std::string_view kFbxFileId{"\x28\xb3\x2a\xeb\xb6\x24\xcc\xc2\xbf\xc8\xb0\x2a\xa9\x2b\xfc\xf1", 16};
inline constexpr std::string_view kFbxCreationTime{"1970-01-01 10:00:00:000"};

// The file's bytes. Fails when a name is longer than 255 bytes or the file would pass 4 GB (the
// limit of 7.4's 32-bit offsets).
Result<std::string> encode_fbx_binary(std::span<const FbxRecord> top);

}  // namespace mg
