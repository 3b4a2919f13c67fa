// JSON documents as text. Parsing (path files, control scripts, API bodies) gives the document
// or an error naming the file and the line where the syntax went wrong, or where a key appears
// a second time in one object (its first value would go unread). Writing never throws:
// names from the input files (joints, clips) may hold bytes that are not UTF-8, such as a
// Latin-1 joint name in a BVH file; they are written as U+FFFD.
#pragma once

#include <initializer_list>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "motiongraph/core/error.h"

namespace mg {

Result<nlohmann::json> parse_json_text(std::string_view text, const std::string& file_name);

// The first key of the object `doc` not among `known` (a misspelt or unknown option), or empty.
std::string unknown_key(const nlohmann::json& doc, std::initializer_list<std::string_view> known);

// The document's text; indent < 0: on one line.
std::string json_text(const nlohmann::json& doc, int indent = -1);

// A cap whose negative value means none (a maximum threshold, a maximum bridge distance): null
// when there is none. Reading takes null, a missing key or an older file's negative number as
// none (-1).
nlohmann::json cap_json(double cap);
double cap_from_json(const nlohmann::json& object, const char* key);

// The text as valid UTF-8, as json_text writes it: each byte that is not becomes U+FFFD (for
// formats whose strings must be UTF-8: glTF's JSON, FBX's names).
std::string valid_utf8(const std::string& text);

}  // namespace mg
