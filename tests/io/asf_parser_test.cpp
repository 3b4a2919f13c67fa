#include "motiongraph/io/asf_parser.h"

#include <gtest/gtest.h>

#include "test_data.h"

namespace mg {
namespace {

// A small but complete ASF: two bones, limits over two lines, a comment, several children.
constexpr const char* kMiniAsf = R"(# a comment
:version 1.10
:name test
:units
  mass 1.0
  length 0.45
  angle deg
:documentation
  free text : with colons
:root
   order TX TY TZ RX RY RZ
   axis XYZ
   position 0 0 0
   orientation 0 0 0
:bonedata
  begin
     id 1
     name a
     direction 0 0 1
     length 2
     axis 0 0 90 XYZ
    dof rx rz
    limits (-160.0 20.0)
           (-inf inf)
  end
  begin
     id 2
     name b
     direction 1 0 0
     length 1.5
     axis 0 0 0 ZYX
  end
  begin
     id 3
     name c
     direction 0 1 0
     length 1
     axis 0 0 0 XYZ
    dof ry
  end
:hierarchy
  begin
    root a c
    a b
  end
)";

TEST(AsfParser, ReadsEveryField) {
  auto doc = parse_asf(kMiniAsf, "mini.asf");
  ASSERT_TRUE(doc) << doc.error().to_string();
  EXPECT_DOUBLE_EQ(doc->length, 0.45);
  EXPECT_TRUE(doc->angles_in_degrees);
  ASSERT_EQ(doc->root.order.size(), 6u);
  EXPECT_EQ(doc->root.order[3], AcclaimDof::kRx);
  ASSERT_EQ(doc->bones.size(), 3u);
  const AsfBone& a = doc->bones[0];
  EXPECT_EQ(a.name, "a");
  EXPECT_EQ(a.line, 16);
  EXPECT_EQ(a.direction, Vec3(0, 0, 1));
  EXPECT_EQ(a.length, 2.0);
  EXPECT_EQ(a.axis, Vec3(0, 0, 90));
  ASSERT_EQ(a.dofs.size(), 2u);
  EXPECT_EQ(a.dofs[1], AcclaimDof::kRz);
  ASSERT_EQ(a.limits.size(), 2u);
  EXPECT_EQ(a.limits[0].first, -160.0);
  EXPECT_TRUE(std::isinf(a.limits[1].second));
  EXPECT_EQ(doc->bones[1].axis_order, (std::array<Axis, 3>{Axis::kZ, Axis::kY, Axis::kX}));
  ASSERT_EQ(doc->hierarchy.size(), 2u);
  EXPECT_EQ(doc->hierarchy[0].children, (std::vector<std::string>{"a", "c"}));
}

TEST(AsfParser, CrlfReadsTheSame) {
  std::string crlf;
  for (char c : std::string(kMiniAsf)) {
    if (c == '\n') crlf += '\r';
    crlf += c;
  }
  auto doc = parse_asf(crlf, "crlf.asf");
  ASSERT_TRUE(doc) << doc.error().to_string();
  EXPECT_EQ(doc->bones.size(), 3u);
  EXPECT_EQ(doc->bones[2].dofs.size(), 1u);
}

TEST(AsfParser, ReadsTheBundledSkeleton) {
  auto doc = parse_asf(test::read_data("cmu/16/16.asf"), "16.asf");
  ASSERT_TRUE(doc) << doc.error().to_string();
  EXPECT_EQ(doc->bones.size(), 30u);
  EXPECT_DOUBLE_EQ(doc->length, 0.45);
  EXPECT_EQ(doc->bones[1].name, "lfemur");
  EXPECT_EQ(doc->bones[1].limits.size(), 3u);
}

TEST(AsfParser, OneCleanErrorPerRule) {
  const std::string base = kMiniAsf;
  const std::vector<test::ErrorCase> cases = {
      {"text outside a section", "hello\n" + base, 1, "expected a section"},
      {"no root", test::replace_once(base, ":root", ":ignored"), 0, "no ':root'"},
      {"root without order", test::replace_once(base, "   order TX TY TZ RX RY RZ\n", ""), 10, "no 'order'"},
      {"bad number", test::replace_once(base, "direction 0 0 1", "direction 0 x 1"), 19, "not a finite number"},
      {"nan", test::replace_once(base, "length 2", "length nan"), 20, "not a finite number"},
      {"overflow", test::replace_once(base, "length 2", "length 1e400"), 20, "not a finite number"},
      {"negative length", test::replace_once(base, "length 2", "length -2"), 20, "negative"},
      {"too few numbers", test::replace_once(base, "direction 0 0 1", "direction 0 0"), 19, "takes 3 values"},
      {"axis order", test::replace_once(base, "axis 0 0 90 XYZ", "axis 0 0 90 XYX"), 21, "permutation"},
      {"unknown dof", test::replace_once(base, "dof rx rz", "dof rx rq"), 22, "unknown degree of freedom"},
      {"repeated dof", test::replace_once(base, "dof rx rz", "dof rx rx"), 22, "listed twice"},
      {"limits count", test::replace_once(base, "           (-inf inf)\n", ""), 16, "limits for 2 dofs"},
      {"limits min > max", test::replace_once(base, "(-160.0 20.0)", "(20.0 -160.0)"), 23, "min > max"},
      {"unknown bone field", test::replace_once(base, "     id 2", "     colour 2"), 27, "unknown bone field"},
      {"bone without end", test::replace_once(base, "    dof ry\n  end", "    dof ry\n"), 33, "no 'end'"},
      {"bone without name", test::replace_once(base, "     name b\n", ""), 26, "no 'name'"},
      {"bone without direction", test::replace_once(base, "     direction 1 0 0\n", ""), 26, "no 'direction'"},
      {"units", test::replace_once(base, "angle deg", "angle grad"), 7, "neither deg nor rad"},
      {"zero length unit", test::replace_once(base, "length 0.45", "length 0"), 6, "must be positive"},
      {"hierarchy without begin", test::replace_once(base, ":hierarchy\n  begin\n", ":hierarchy\n"), 42, "must start with 'begin'"},
      {"hierarchy without end", test::replace_once(base, "    a b\n  end\n", "    a b\n"), 44, "no 'end'"},
      {"hierarchy without children", test::replace_once(base, "    a b\n", "    a\n"), 44, "names no children"},
      {"section twice", base + ":units\n  mass 1\n", 46, "appears twice"},
  };
  for (const auto& c : cases) {
    auto doc = parse_asf(c.text, "bad.asf");
    ASSERT_FALSE(doc) << c.rule;
    EXPECT_EQ(doc.error().file, "bad.asf") << c.rule;
    test::expect_error_matches(doc.error(), c);
  }
}

}  // namespace
}  // namespace mg
