// Parsing a JSON document given as text (path files, control scripts, API bodies): the
// document, or an error naming the file and the line where the syntax went wrong.
#pragma once

#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "motiongraph/core/error.h"

namespace mg {

Result<nlohmann::json> parse_json_text(std::string_view text, const std::string& file_name);

}  // namespace mg
