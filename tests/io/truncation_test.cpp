// Every prefix of a real file parses or fails cleanly: never a crash, a hang or an error
// without a message or with a line beyond the text. Byte by byte for small real files (the
// ASF, and the first frames of an AMC and a BVH cut into files of their own), line by line for
// whole bundled files (the first 400 lines, then every 97th).
#include <algorithm>

#include <gtest/gtest.h>

#include "motiongraph/io/amc_parser.h"
#include "motiongraph/io/asf_parser.h"
#include "motiongraph/io/bvh_parser.h"
#include "motiongraph/motion/acclaim_import.h"
#include "motiongraph/motion/bvh_import.h"
#include "test_data.h"

namespace mg {
namespace {

int count_lines(std::string_view text) { return static_cast<int>(std::count(text.begin(), text.end(), '\n')) + 1; }

template <class T>
void expect_clean(const Result<T>& result, std::string_view prefix) {
  if (result.ok()) return;
  const Error& e = result.error();
  ASSERT_FALSE(e.message.empty()) << "prefix of " << prefix.size() << " bytes";
  ASSERT_GE(e.line, 0);
  ASSERT_LE(e.line, count_lines(prefix)) << e.to_string();
}

AcclaimRig bundled_rig() {
  auto asf = parse_asf(test::read_data("cmu/16/16.asf"), "16.asf");
  return *build_acclaim_rig(*asf);
}

void check_asf(std::string_view prefix) {
  auto doc = parse_asf(prefix, "p.asf");
  expect_clean(doc, prefix);
  if (doc) expect_clean(build_acclaim_rig(*doc), prefix);
}

void check_amc(std::string_view prefix, const AcclaimRig& rig) {
  expect_clean(parse_amc(prefix, "p.amc", rig.amc_layout, true), prefix);
}

void check_bvh(std::string_view prefix) {
  auto doc = parse_bvh(prefix, "p.bvh");
  expect_clean(doc, prefix);
  if (doc) expect_clean(clip_from_bvh(*doc, {}), prefix);
}

// The text up to the end of line `lines` (1-based).
std::string first_lines(const std::string& text, int lines) {
  size_t at = 0;
  for (int n = 0; n < lines && at != std::string::npos; ++n) at = text.find('\n', at + (n ? 1 : 0));
  return text.substr(0, at == std::string::npos ? text.size() : at + 1);
}

TEST(Truncation, EveryBytePrefixOfTheAsf) {
  const std::string text = test::read_data("cmu/16/16.asf");
  for (size_t n = 0; n <= text.size(); ++n) check_asf(std::string_view(text).substr(0, n));
}

TEST(Truncation, EveryBytePrefixOfShortAmcAndBvh) {
  const AcclaimRig rig = bundled_rig();
  // Two frames of 16_01.amc: 3 header lines, then 30 lines per frame.
  const std::string amc = first_lines(test::read_data("cmu/16/16_01.amc"), 3 + 2 * 30);
  for (size_t n = 0; n <= amc.size(); ++n) check_amc(std::string_view(amc).substr(0, n), rig);
  // The hierarchy and two frames of 131_01.bvh (CRLF), with its Frames: line made to match.
  std::string bvh = test::read_data("bvh/131_01.bvh");
  const size_t motion = bvh.find("MOTION");
  bvh = first_lines(bvh, count_lines(bvh.substr(0, motion)) + 4);
  bvh.replace(bvh.find("Frames: 994"), 11, "Frames: 2");
  ASSERT_TRUE(parse_bvh(bvh, "short.bvh"));
  for (size_t n = 0; n <= bvh.size(); ++n) check_bvh(std::string_view(bvh).substr(0, n));
}

// Ends of the first 400 lines, then of every 97th line (whole-file parses are not free).
std::vector<size_t> line_ends(const std::string& text) {
  std::vector<size_t> ends;
  int line = 0;
  for (size_t at = text.find('\n'); at != std::string::npos; at = text.find('\n', at + 1)) {
    if (++line <= 400 || line % 97 == 0) ends.push_back(at);
  }
  return ends;
}

TEST(Truncation, LinePrefixesOfWholeFiles) {
  const AcclaimRig rig = bundled_rig();
  const std::string amc = test::read_data("cmu/16/16_35.amc");
  for (size_t at : line_ends(amc)) {
    check_amc(std::string_view(amc).substr(0, at + 1), rig);
    check_amc(std::string_view(amc).substr(0, at), rig);  // without its newline
    check_amc(std::string_view(amc).substr(0, at > 3 ? at - 3 : 0), rig);  // a cut number
  }
  const std::string bvh = test::read_data("bvh/16_01.bvh");
  for (size_t at : line_ends(bvh)) {
    check_bvh(std::string_view(bvh).substr(0, at + 1));
    check_bvh(std::string_view(bvh).substr(0, at > 3 ? at - 3 : 0));
  }
}

}  // namespace
}  // namespace mg
