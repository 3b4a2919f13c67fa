#include "motiongraph/core/json_text.h"

#include <algorithm>

namespace mg {

Result<nlohmann::json> parse_json_text(std::string_view text, const std::string& file_name) {
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    const size_t pos = std::min<size_t>(e.byte, text.size());
    const auto begin = text.begin();
    const int line = 1 + static_cast<int>(std::count(begin, begin + static_cast<std::ptrdiff_t>(pos), '\n'));
    return Error{file_name, line, "not valid JSON"};
  }
}

std::string json_text(const nlohmann::json& doc, int indent) {
  return doc.dump(indent, ' ', false, nlohmann::json::error_handler_t::replace);
}

}  // namespace mg
