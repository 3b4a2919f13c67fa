// Reading text formats line by line: LF, CRLF or CR endings, tabs and spaces as separators,
// numbers parsed strictly (whole token, finite). Used by the ASF, AMC and BVH parsers, which
// all take the file's text in memory plus its name for messages.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "motiongraph/core/error.h"

namespace mg {

// Splits a line into whitespace-separated tokens (spaces, tabs, \r, \v, \f).
std::vector<std::string_view> split_tokens(std::string_view line);

// A token parsed as a finite double; nullopt for anything else ("1.5x", "nan", "inf", "").
// Accepts a leading '+' and forms like ".5" and "1e-3".
std::optional<double> parse_finite(std::string_view token);

// A token parsed as an int (decimal, optional sign); nullopt when not exactly that or when
// it does not fit.
std::optional<long long> parse_integer(std::string_view token);

// Walks text line by line. Line numbers are 1-based; a trailing '\r' is removed. Lines end
// with LF (CRLF), or with CR alone in a text that has no LF; a UTF-8 byte-order mark first is
// skipped.
class LineReader {
 public:
  LineReader(std::string_view text, std::string file_name);

  // The next line, or nullopt at the end of the text.
  std::optional<std::string_view> next();
  // The next line that has a token, as tokens (skips blank lines); empty at the end.
  std::vector<std::string_view> next_tokens();
  // Looks at the next non-blank line's tokens without consuming it.
  std::vector<std::string_view> peek_tokens();

  int line_number() const { return line_number_; }  // number of the line last returned
  bool at_end() const { return pos_ >= text_.size(); }
  // Remaining text, unread.
  std::string_view rest() const { return text_.substr(pos_); }
  const std::string& file_name() const { return file_; }

  // An error at the line last returned.
  Error error(std::string message) const { return Error{file_, line_number_, std::move(message)}; }
  Error error_at(int line, std::string message) const { return Error{file_, line, std::move(message)}; }

 private:
  std::string_view text_;
  std::string file_;
  size_t pos_ = 0;
  int line_number_ = 0;
  char line_end_ = '\n';
};

// Quotes a token for an error message: at most 40 characters (then "..."), control bytes and
// bytes that are not well-formed UTF-8 escaped (\t, \n, \r, \xNN), so a binary file's bytes never
// reach the terminal raw.
std::string quoted(std::string_view token);

// ASCII letters only, whatever the locale (names split at case changes: "LeftUpLeg").
inline bool is_ascii_upper(char c) { return c >= 'A' && c <= 'Z'; }
inline bool is_ascii_lower(char c) { return c >= 'a' && c <= 'z'; }
inline bool is_ascii_letter(char c) { return is_ascii_upper(c) || is_ascii_lower(c); }
inline bool is_ascii_digit(char c) { return c >= '0' && c <= '9'; }
// One or more ASCII digits and nothing else (no sign, space or base prefix).
inline bool is_ascii_digits(std::string_view text) {
  if (text.empty()) return false;
  for (const char c : text) {
    if (!is_ascii_digit(c)) return false;
  }
  return true;
}

// `text` with its ASCII letters in lower case (other bytes as they are): names and keywords
// compared whatever their case.
std::string ascii_lower(std::string_view text);

}  // namespace mg
