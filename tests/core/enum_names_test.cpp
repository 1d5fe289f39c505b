// The enum-name tables (core/enum_names.h): naming, parsing, the error for a name that is not in the
// table, and the lists of help texts, on a table of the test's own.
#include "roadbrdf/core/enum_names.h"

#include <gtest/gtest.h>

#include <span>
#include <string>

#include "roadbrdf/core/error.h"

namespace roadbrdf {
namespace {

enum class Grain { kSand, kGravel, kCobble };
constexpr EnumName<Grain> kGrainNames[] = {
    {Grain::kSand, "sand", "below 2 mm"},
    {Grain::kGravel, "gravel", "2 to 64 mm"},
    {Grain::kCobble, "cobble", ""},
};
constexpr std::span<const EnumName<Grain>> enum_names(Grain) { return kGrainNames; }

// The detail of the FieldError `parse` throws, with its field.
template <typename Parse>
std::pair<std::string, std::string> field_error(Parse parse) {
  try {
    parse();
  } catch (const FieldError& e) {
    return {e.field(), e.detail()};
  }
  return {"", "no FieldError"};
}

TEST(EnumNames, NameAndParseAreInverse) {
  EXPECT_EQ(name_of(Grain::kSand), "sand");
  EXPECT_EQ(name_of(Grain::kGravel), "gravel");
  EXPECT_EQ(name_of(Grain::kCobble), "cobble");
  EXPECT_EQ(parse_name<Grain>("sand", "grain"), Grain::kSand);
  EXPECT_EQ(parse_name<Grain>("gravel", "grain"), Grain::kGravel);
  EXPECT_EQ(parse_name<Grain>("cobble", "grain"), Grain::kCobble);
  EXPECT_EQ(description_of(Grain::kGravel), "2 to 64 mm");
  EXPECT_EQ(description_of(Grain::kCobble), "");
}

TEST(EnumNames, ListsFollowTheTableOrder) {
  EXPECT_EQ(names_of<Grain>(), (std::vector<std::string>{"sand", "gravel", "cobble"}));
  EXPECT_EQ(values_of<Grain>(), (std::vector<Grain>{Grain::kSand, Grain::kGravel, Grain::kCobble}));
  EXPECT_EQ(names_text<Grain>(), "sand, gravel or cobble");
  EXPECT_EQ(described_names_text<Grain>(), "sand (below 2 mm), gravel (2 to 64 mm) or cobble");
}

TEST(EnumNames, AnUnknownNameIsAnErrorOfTheFieldListingTheNames) {
  EXPECT_EQ(field_error([] { parse_name<Grain>("gravle", "options.grain"); }),
            std::make_pair(std::string("options.grain"),
                           std::string("'gravle' is not one of sand, gravel, cobble (did you mean 'gravel'?)")));
  // Nothing near: no suggestion. Parsing is exact: neither the letter case nor spaces are forgiven.
  EXPECT_EQ(field_error([] { parse_name<Grain>("boulder", "grain"); }).second,
            "'boulder' is not one of sand, gravel, cobble");
  EXPECT_EQ(field_error([] { parse_name<Grain>("Sand", "grain"); }).second,
            "'Sand' is not one of sand, gravel, cobble (did you mean 'sand'?)");
  EXPECT_EQ(field_error([] { parse_name<Grain>("", "grain"); }).second, "'' is not one of sand, gravel, cobble");
  try {
    parse_name<Grain>("silt", "grain");
    ADD_FAILURE() << "no error";
  } catch (const FieldError& e) {
    EXPECT_STREQ(e.what(), "grain: 'silt' is not one of sand, gravel, cobble");
  }
}

TEST(EnumNames, AValueMissingFromItsTableIsAnInternalError) {
  EXPECT_THROW(name_of(static_cast<Grain>(7)), std::logic_error);
}

TEST(EnumNames, DistinctEntriesAreCheckedAtCompileTime) {
  constexpr EnumName<Grain> same_name[] = {{Grain::kSand, "sand", ""}, {Grain::kGravel, "sand", ""}};
  constexpr EnumName<Grain> same_value[] = {{Grain::kSand, "sand", ""}, {Grain::kSand, "gravel", ""}};
  constexpr EnumName<Grain> no_name[] = {{Grain::kSand, "", ""}};
  static_assert(entries_are_distinct(kGrainNames));
  static_assert(!entries_are_distinct(same_name));
  static_assert(!entries_are_distinct(same_value));
  static_assert(!entries_are_distinct(no_name));
}

}  // namespace
}  // namespace roadbrdf
