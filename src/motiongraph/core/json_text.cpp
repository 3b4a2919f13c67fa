#include "motiongraph/core/json_text.h"

#include <algorithm>
#include <map>
#include <set>
#include <vector>

#include <fmt/format.h>

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

nlohmann::json cap_json(double cap) { return cap < 0.0 ? nlohmann::json(nullptr) : nlohmann::json(cap); }

double cap_from_json(const nlohmann::json& object, const char* key) {
  const auto cap = object.find(key);
  if (cap == object.end() || cap->is_null()) return -1.0;
  return std::max(cap->get<double>(), -1.0);
}

Result<nlohmann::json> parse_json_text(std::string_view text, const std::string& file_name) {
  // A key twice in one object: nlohmann keeps the last, and a script's first "duration_s" or a
  // path's first "points" went unread without a word. Each open object's keys, innermost last.
  std::vector<std::set<std::string>> keys;
  std::map<std::string, int> seen;  // how many times each key was read, for the line of a repeat
  struct Repeated {
    std::string key;
    int nth = 0;
  };
  auto callback = [&](int, nlohmann::json::parse_event_t event, nlohmann::json& parsed) {
    using Event = nlohmann::json::parse_event_t;
    if (event == Event::object_start) keys.emplace_back();
    if (event == Event::object_end && !keys.empty()) keys.pop_back();
    if (event == Event::key && !keys.empty()) {
      const std::string key = parsed.get<std::string>();
      const int nth = ++seen[key];
      if (!keys.back().insert(key).second) throw Repeated{key, nth};
    }
    return true;
  };
  try {
    return nlohmann::json::parse(text, callback);
  } catch (const Repeated& repeated) {
    // Its line: the nth time the key is written as a key (quoted, then a colon).
    const std::string quoted = nlohmann::json(repeated.key).dump();
    size_t at = std::string_view::npos;
    for (size_t from = 0, found = 0; found < static_cast<size_t>(repeated.nth);) {
      at = text.find(quoted, from);
      if (at == std::string_view::npos) break;
      from = at + quoted.size();
      const size_t next = text.find_first_not_of(" \t\r\n", from);
      if (next != std::string_view::npos && text[next] == ':') ++found;
    }
    return Error{file_name, at == std::string_view::npos ? 0 : line_at(text, at),
                 fmt::format("the key {} appears twice in one object", quoted)};
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
