#include "motiongraph/core/text.h"

#include <charconv>
#include <cmath>
#include <limits>

namespace mg {

namespace {
bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }
}  // namespace

std::vector<std::string_view> split_tokens(std::string_view line) {
  std::vector<std::string_view> tokens;
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && is_space(line[i])) ++i;
    size_t start = i;
    while (i < line.size() && !is_space(line[i])) ++i;
    if (i > start) tokens.push_back(line.substr(start, i - start));
  }
  return tokens;
}

std::optional<double> parse_finite(std::string_view token) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  if (token.empty() || token.front() == '+') return std::nullopt;
  double value = 0.0;
  const char* end = token.data() + token.size();
  auto [ptr, ec] = std::from_chars(token.data(), end, value, std::chars_format::general);
  if (ec != std::errc() || ptr != end || !std::isfinite(value)) return std::nullopt;
  return value;
}

std::optional<long long> parse_integer(std::string_view token) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  if (token.empty() || token.front() == '+') return std::nullopt;
  long long value = 0;
  const char* end = token.data() + token.size();
  auto [ptr, ec] = std::from_chars(token.data(), end, value);
  if (ec != std::errc() || ptr != end) return std::nullopt;
  return value;
}

LineReader::LineReader(std::string_view text, std::string file_name)
    : text_(text), file_(std::move(file_name)) {}

std::optional<std::string_view> LineReader::next() {
  if (pos_ >= text_.size()) return std::nullopt;
  size_t end = text_.find('\n', pos_);
  if (end == std::string_view::npos) end = text_.size();
  std::string_view line = text_.substr(pos_, end - pos_);
  pos_ = end + 1;
  ++line_number_;
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  return line;
}

std::vector<std::string_view> LineReader::next_tokens() {
  while (auto line = next()) {
    auto tokens = split_tokens(*line);
    if (!tokens.empty()) return tokens;
  }
  return {};
}

std::vector<std::string_view> LineReader::peek_tokens() {
  LineReader copy = *this;
  return copy.next_tokens();
}

std::string quoted(std::string_view token) {
  constexpr size_t kMax = 40;
  std::string out = "'";
  if (token.size() > kMax) {
    out += token.substr(0, kMax);
    out += "...";
  } else {
    out += token;
  }
  out += "'";
  return out;
}

}  // namespace mg
