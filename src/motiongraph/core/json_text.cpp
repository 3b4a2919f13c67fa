#include "motiongraph/core/json_text.h"

#include <algorithm>

namespace mg {

namespace {

int line_at(std::string_view text, size_t pos) {
  const auto begin = text.begin();
  pos = std::min(pos, text.size());
  return 1 + static_cast<int>(std::count(begin, begin + static_cast<std::ptrdiff_t>(pos), '\n'));
}

}  // namespace

std::string unknown_key(const nlohmann::json& doc, std::initializer_list<std::string_view> known) {
  if (!doc.is_object()) return "";
  for (const auto& [key, value] : doc.items()) {
    if (std::find(known.begin(), known.end(), key) == known.end()) return key;
  }
  return "";
}

Result<nlohmann::json> parse_json_text(std::string_view text, const std::string& file_name) {
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    return Error{file_name, line_at(text, e.byte), "not valid JSON"};
  } catch (const nlohmann::json::out_of_range& e) {
    // A number too large for a double (1e999): the message quotes it, which gives its line.
    const std::string_view what = e.what();
    const size_t open = what.find('\''), close = what.rfind('\'');
    size_t pos = std::string_view::npos;
    if (open != std::string_view::npos && close > open + 1) pos = text.find(what.substr(open + 1, close - open - 1));
    return Error{file_name, pos == std::string_view::npos ? 0 : line_at(text, pos), "a number out of range"};
  } catch (const nlohmann::json::exception&) {
    return Error{file_name, 0, "not valid JSON"};
  }
}

std::string json_text(const nlohmann::json& doc, int indent) {
  return doc.dump(indent, ' ', false, nlohmann::json::error_handler_t::replace);
}

std::string valid_utf8(const std::string& text) {
  return nlohmann::json::parse(json_text(nlohmann::json(text))).get<std::string>();
}

}  // namespace mg
