#include "motiongraph/database/cmu_tags.h"

#include <algorithm>
#include <array>
#include <cctype>

#include <fmt/format.h>

#include "motiongraph/core/text.h"

namespace mg {

namespace {

struct TagWords {
  std::string_view tag;
  std::vector<std::string_view> words;
};

// The vocabulary documented in cmu_tags.h; keep the two in step.
const std::array<TagWords, 11> kTagWords = {{
    {"walk", {"walk", "walks", "walking", "march", "marching", "stride", "stroll", "strolling", "wander",
              "wandering", "sneak", "sneaking", "tiptoe", "tiptoeing", "creep", "creeping", "limp", "limping", "walked",
              "marched", "strolled", "wandered", "sneaked", "snuck", "tiptoed", "crept", "limped"}},
    {"run", {"run", "runs", "running", "jog", "jogs", "jogging", "sprint", "sprinting", "ran", "jogged", "sprinted"}},
    {"jump",
     {"jump", "jumps", "jumping", "hop", "hops", "hopping", "leap", "leaps", "leaping", "jumped", "hopped", "leaped",
      "leapt"}},
    {"turn",
     {"turn", "turns", "turning", "spin", "spins", "spinning", "pivot", "pivoting", "turned", "spun", "pivoted"}},
    {"stop", {"stop", "stops", "stopping", "halt", "stopped", "halted"}},
    {"start", {"start", "starts", "starting", "started"}},
    {"sidestep", {"sidestep", "sidesteps", "sidestepping", "sideways", "sideway", "strafe", "strafes", "strafing",
                  "sidestepped", "strafed"}},
    {"backward", {"backward", "backwards"}},
    {"sit", {"sit", "sits", "sitting", "seated", "sat"}},
    {"climb", {"climb", "climbs", "climbing", "climbed"}},
    {"dance", {"dance", "dances", "dancing", "salsa", "danced"}},
}};

const std::array<std::string_view, kTagWords.size()> kVocabulary = [] {
  std::array<std::string_view, kTagWords.size()> names{};
  for (size_t i = 0; i < kTagWords.size(); ++i) names[i] = kTagWords[i].tag;
  return names;
}();

// Lower-case words: runs of letters, also split where a lower-case letter meets an upper-case
// one ("RunningWideRight" -> running, wide, right).
std::vector<std::string> words_of(std::string_view text) {
  std::vector<std::string> words;
  std::string word;
  auto flush = [&] {
    if (!word.empty()) words.push_back(std::move(word));
    word.clear();
  };
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (!is_ascii_letter(c)) {
      flush();
      continue;
    }
    if (is_ascii_upper(c) && i > 0 && is_ascii_lower(text[i - 1])) flush();
    word += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  flush();
  return words;
}

std::string_view trim(std::string_view s) {
  const auto space = [](char c) { return c == ' ' || c == '\t' || c == '\r'; };
  while (!s.empty() && space(s.front())) s.remove_prefix(1);
  while (!s.empty() && space(s.back())) s.remove_suffix(1);
  return s;
}

std::vector<std::string_view> split_tabs(std::string_view line) {
  std::vector<std::string_view> fields;
  size_t start = 0;
  while (true) {
    const size_t tab = line.find('\t', start);
    fields.push_back(trim(line.substr(start, tab == std::string_view::npos ? std::string_view::npos : tab - start)));
    if (tab == std::string_view::npos) break;
    start = tab + 1;
  }
  return fields;
}

bool is_header_row(std::string_view line) {
  const std::string_view first = split_tabs(line).front();
  return first.size() == 6 && std::equal(first.begin(), first.end(), "MOTION", [](char a, char b) {
           return std::toupper(static_cast<unsigned char>(a)) == b;
         });
}

}  // namespace

std::optional<std::string> cmu_motion_id(std::string_view clip_name) {
  const size_t underscore = clip_name.find('_');
  if (underscore == std::string_view::npos) return std::nullopt;
  const std::string_view subject = clip_name.substr(0, underscore);
  const std::string_view trial = clip_name.substr(underscore + 1);
  const auto digits = [](std::string_view s) {
    return !s.empty() && s.size() <= 6 &&
           std::all_of(s.begin(), s.end(), [](unsigned char c) { return std::isdigit(c) != 0; });
  };
  if (!digits(subject) || !digits(trial)) return std::nullopt;
  return fmt::format("{:02}_{:02}", std::stoi(std::string(subject)), std::stoi(std::string(trial)));
}

const CmuMotion* CmuIndex::find(std::string_view clip_name) const {
  auto id = cmu_motion_id(clip_name);
  if (!id) return nullptr;
  auto it = by_id.find(*id);
  return it == by_id.end() ? nullptr : &motions[static_cast<size_t>(it->second)];
}

Result<CmuIndex> parse_cmu_index(std::string_view tsv_text, std::string file_name) {
  // Everything before the header row, when there is one, is the listing's preamble (Hahne's
  // has a note spread over several lines, not all of them marked with '#').
  bool has_header = false;
  {
    LineReader scan(tsv_text, file_name);
    while (auto line = scan.next()) {
      if (is_header_row(*line)) {
        has_header = true;
        break;
      }
    }
  }
  CmuIndex index;
  LineReader in(tsv_text, std::move(file_name));
  bool in_preamble = has_header;
  while (auto line = in.next()) {
    if (in_preamble) {
      in_preamble = !is_header_row(*line);
      continue;
    }
    if (trim(*line).empty() || trim(*line).front() == '#') continue;
    const std::vector<std::string_view> fields = split_tabs(*line);
    if (fields.size() < 2) {
      return in.error(fmt::format("expected MOTION<tab>DESCRIPTION<tab>SUBJECT, found no tab in {}",
                                  quoted(trim(*line))));
    }
    if (fields.size() > 3) return in.error(fmt::format("{} columns; expected at most 3", fields.size()));
    auto id = cmu_motion_id(fields[0]);
    if (!id || *id != fields[0]) {
      return in.error(fmt::format("motion id {} is not of the form <subject>_<trial>, e.g. 16_15",
                                  quoted(fields[0])));
    }
    const int position = static_cast<int>(index.motions.size());
    auto [it, inserted] = index.by_id.emplace(*id, position);
    if (!inserted) {
      return in.error(fmt::format("motion {} is listed twice (first on line {})", *id,
                                  index.motions[static_cast<size_t>(it->second)].line));
    }
    index.motions.push_back(CmuMotion{*id, std::string(fields[1]),
                                      fields.size() > 2 ? std::string(fields[2]) : std::string(), in.line_number()});
  }
  return index;
}

std::vector<std::string> cmu_description_tags(std::string_view description) {
  const std::vector<std::string> words = words_of(description);
  std::vector<std::string> tags;
  for (const TagWords& entry : kTagWords) {
    const bool found = std::any_of(words.begin(), words.end(), [&](const std::string& word) {
      return std::find(entry.words.begin(), entry.words.end(), word) != entry.words.end();
    });
    if (found) tags.emplace_back(entry.tag);
  }
  return tags;
}

std::vector<std::string> clip_name_tags(std::string_view name) { return cmu_description_tags(name); }

std::span<const std::string_view> cmu_tag_vocabulary() { return kVocabulary; }

}  // namespace mg
