// The one grammar of number lists (core/range.h), the one reading of a number (core/number.h) and the
// nearest-name helper (core/nearest_name.h).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/nearest_name.h"
#include "roadbrdf/core/number.h"
#include "roadbrdf/core/range.h"

namespace roadbrdf {
namespace {

std::string message_of(const std::string& text, const RangeRules& rules = {}) {
  try {
    parse_range_list(text, "--sun-zenith", rules);
  } catch (const FieldError& e) {
    EXPECT_EQ(e.field(), "--sun-zenith");
    return e.what();
  }
  return "";
}

TEST(Range, NumbersListsRangesAndMixes) {
  EXPECT_EQ(parse_range_list("30", "x"), (std::vector<double>{30}));
  EXPECT_EQ(parse_range_list("400,500", "x"), (std::vector<double>{400, 500}));
  EXPECT_EQ(parse_range_list("0:60:30", "x"), (std::vector<double>{0, 30, 60}));
  EXPECT_EQ(parse_range_list("5:5:1", "x"), (std::vector<double>{5}));
  EXPECT_EQ(parse_range_list(" 400:420:10 , 500 ", "x"), (std::vector<double>{400, 410, 420, 500}));
  EXPECT_EQ(parse_range_list("60,0:20:10", "x"), (std::vector<double>{60, 0, 10, 20}));  // order kept
  // The last value is STOP itself, not START + n STEP rounded: 0.1 * 3 != 0.3 in binary.
  const std::vector<double> tenths = parse_range_list("0:0.3:0.1", "x");
  ASSERT_EQ(tenths.size(), 4u);
  EXPECT_EQ(tenths.back(), 0.3);
  EXPECT_EQ(parse_range_list("350:2490:20", "x").size(), 108u);  // (2490 - 350) / 20 + 1
}

TEST(Range, IntervalsAreLowerColonUpper) {
  EXPECT_EQ(parse_interval("590:610", "--band"), (std::pair<double, double>{590.0, 610.0}));
  EXPECT_EQ(parse_interval(" -1.5 : 2e1 ", "bounds.x"), (std::pair<double, double>{-1.5, 20.0}));
  EXPECT_EQ(parse_interval("3:3", "--drop"), (std::pair<double, double>{3.0, 3.0}));
  auto message = [](const std::string& text) {
    try {
      parse_interval(text, "--band");
    } catch (const FieldError& e) {
      EXPECT_EQ(e.field(), "--band");
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(message("600"), "--band: expected LOWER:UPPER, got '600'");
  EXPECT_EQ(message("1:2:3"), "--band: expected LOWER:UPPER, got '1:2:3'");
  EXPECT_EQ(message("610:590"), "--band: '610:590': LOWER is above UPPER");
  EXPECT_EQ(message("a:610"), "--band: 'a' in 'a:610' is not a finite number");
  EXPECT_EQ(message("590:inf"), "--band: 'inf' in '590:inf' is not a finite number");
}

TEST(Range, BothEndsIncludedOrAnError) {
  const std::string m = message_of("0:50:30");
  EXPECT_NE(m.find("--sun-zenith: '0:50:30'"), std::string::npos) << m;
  EXPECT_NE(m.find("not a whole number of STEPs"), std::string::npos) << m;
  EXPECT_NE(m.find("0:30:30"), std::string::npos) << m;  // suggestions on both sides
  EXPECT_NE(m.find("0:60:30"), std::string::npos) << m;
}

TEST(Range, BadTextIsAnErrorNamingTheFieldAndTheText) {
  EXPECT_NE(message_of("0:1e30:1").find("more than 100000 values"), std::string::npos);
  EXPECT_NE(message_of("0:1:1e-300").find("more than 100000 values"), std::string::npos);
  EXPECT_NE(message_of("0:10:0").find("STEP must be > 0"), std::string::npos);
  EXPECT_NE(message_of("0:10:-5").find("STEP must be > 0"), std::string::npos);
  EXPECT_NE(message_of("10:0:5").find("STOP is below START"), std::string::npos);
  EXPECT_NE(message_of("0:nan:5").find("'nan' in '0:nan:5' is not a finite number"), std::string::npos);
  EXPECT_NE(message_of("inf").find("'inf' is not a finite number"), std::string::npos);
  EXPECT_NE(message_of("1:2").find("a range is START:STOP:STEP"), std::string::npos);
  EXPECT_NE(message_of("1:2:3:4").find("a range is START:STOP:STEP"), std::string::npos);
  EXPECT_NE(message_of("10,,20").find("empty item"), std::string::npos);
  EXPECT_NE(message_of("").find("no value given"), std::string::npos);
  EXPECT_NE(message_of("10,0:20:10").find("10 is given twice"), std::string::npos);
  EXPECT_NE(message_of("3x").find("'3x' is not a finite number"), std::string::npos);
}

TEST(Range, Rules) {
  EXPECT_NE(message_of("500,400", wavelength_rules()).find("must increase"), std::string::npos);
  EXPECT_NE(message_of("0:100:50", wavelength_rules()).find("0 must be > 0 nm"), std::string::npos);
  RangeRules zenith;
  zenith.lower = 0.0;
  zenith.upper = 89.0;
  zenith.unit = "deg";
  EXPECT_NE(message_of("0:90:30", zenith).find("90 deg is outside [0, 89] deg"), std::string::npos);
  RangeRules few;
  few.max_count = 3;
  EXPECT_NE(message_of("0:30:10", few).find("more than 3 values"), std::string::npos);
  EXPECT_NE(message_of("1,2,3,4", few).find("more than 3 values"), std::string::npos);
  EXPECT_THROW(check_range_values({1.0, 1.0}, "x"), FieldError);
  EXPECT_NO_THROW(check_range_values({3.0, 1.0}, "x"));
}

TEST(NearestName, EditDistanceByHand) {
  EXPECT_EQ(edit_distance("", ""), 0u);
  EXPECT_EQ(edit_distance("fit", "fit"), 0u);
  EXPECT_EQ(edit_distance("fti", "fit"), 1u);         // one transposition
  EXPECT_EQ(edit_distance("kitten", "sitting"), 3u);  // the textbook example: k->s, e->i, +g
  EXPECT_EQ(edit_distance("abc", ""), 3u);
}

TEST(NearestName, SuggestsOnlyCloseNames) {
  const std::vector<std::string> commands = {"models", "eval", "fit", "simulate", "albedo", "rtable"};
  EXPECT_EQ(nearest_name("fti", commands), "fit");
  EXPECT_EQ(nearest_name("simulte", commands), "simulate");
  EXPECT_EQ(nearest_name("alb", commands), "albedo");  // a unique prefix
  EXPECT_EQ(nearest_name("zzzzzz", commands), "");
  const std::vector<std::string> flags = {"--sun-zenith", "--sun-azimuth", "--json", "-o"};
  EXPECT_EQ(nearest_name("--sun-zenit", flags), "--sun-zenith");
  EXPECT_EQ(nearest_name("--sun", flags), "");  // ambiguous prefix
  EXPECT_EQ(did_you_mean("--jsn", flags), " (did you mean '--json'?)");
  EXPECT_EQ(did_you_mean("--colour", flags), "");
}

// A leading '+' is part of how people write numbers: "+0" is read like "+0.1" (once; "+-1" is not).
TEST(Number, WholeTextFiniteWithOptionalPlus) {
  double v = -1.0;
  EXPECT_TRUE(parse_finite_double("+0", v));
  EXPECT_EQ(v, 0.0);
  EXPECT_TRUE(parse_finite_double("+0.1", v));
  EXPECT_EQ(v, 0.1);
  EXPECT_TRUE(parse_finite_double("-2.5e-3", v));
  EXPECT_EQ(v, -2.5e-3);
  for (const char* bad : {"", "+", "++1", "+-1", "1.5x", " 1", "1e400", "inf", "nan", "4OO"}) {
    EXPECT_FALSE(parse_finite_double(bad, v)) << bad;
  }
  // Numbers that are written as numbers but are not finite still tell a data row from a header.
  for (const char* number : {"1e400", "-1e400", "inf", "+0", "3"}) EXPECT_TRUE(is_number_text(number)) << number;
  for (const char* text : {"wavelength", "4OO", "", "+", "1,5"}) EXPECT_FALSE(is_number_text(text)) << text;
  EXPECT_EQ(parse_range_list("+0:+60:+30", "x"), (std::vector<double>{0, 30, 60}));
}

}  // namespace
}  // namespace roadbrdf
