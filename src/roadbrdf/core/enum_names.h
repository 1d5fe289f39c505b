// The names of an enumeration's values, declared once: one table per enumeration gives each value its
// name (what files, requests, the command line and Python spell) and a short description (for help
// texts). Parsing, naming, error messages and help texts are all read from that table, so that the
// command line and Python accept the same names and report a wrong one with the same message.
//
// An enumeration takes part by a table and a function found by argument-dependent lookup, both
// next to the enumeration:
//
//   enum class FitLoss { kPlain, kRelative };
//   inline constexpr EnumName<FitLoss> kFitLossNames[] = {
//       {FitLoss::kPlain, "plain", "f-y"},
//       {FitLoss::kRelative, "relative", "(f-y)/y"},
//   };
//   constexpr std::span<const EnumName<FitLoss>> enum_names(FitLoss) { return kFitLossNames; }
//
// then name_of(FitLoss::kRelative) is "relative", parse_name<FitLoss>("relative", "loss") is
// FitLoss::kRelative, parse_name<FitLoss>("relativ", "loss") throws FieldError("loss", "'relativ' is
// not one of plain, relative (did you mean 'relative'?)"), and described_names_text<FitLoss>() is
// "plain (f-y) or relative ((f-y)/y)". The table's order is the order of every list.
#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/nearest_name.h"

namespace roadbrdf {

template <typename Enum>
struct EnumName {
  Enum value;
  std::string_view name;
  std::string_view description;  // a few words for help texts; may be empty
};

// The table of Enum, through the enum_names(Enum) declared next to it.
template <typename Enum>
constexpr std::span<const EnumName<Enum>> names_table() {
  return enum_names(Enum{});
}

// True when no two entries of a table share a value or a name, and every name is given: for a
// static_assert next to a table that no test reaches.
template <typename Enum, std::size_t N>
constexpr bool entries_are_distinct(const EnumName<Enum> (&table)[N]) {
  for (std::size_t i = 0; i < N; ++i) {
    if (table[i].name.empty()) return false;
    for (std::size_t j = 0; j < i; ++j) {
      if (table[i].value == table[j].value || table[i].name == table[j].name) return false;
    }
  }
  return true;
}

// The entry of a value. A value missing from its table is a programming error (std::logic_error).
template <typename Enum>
const EnumName<Enum>& entry_of(Enum value) {
  for (const EnumName<Enum>& entry : names_table<Enum>()) {
    if (entry.value == value) return entry;
  }
  throw std::logic_error("a value has no name in its enumeration's table");
}

template <typename Enum>
std::string name_of(Enum value) {
  return std::string(entry_of(value).name);
}

template <typename Enum>
std::string description_of(Enum value) {
  return std::string(entry_of(value).description);
}

// The names in table order.
template <typename Enum>
std::vector<std::string> names_of() {
  std::vector<std::string> names;
  for (const EnumName<Enum>& entry : names_table<Enum>()) names.emplace_back(entry.name);
  return names;
}

// The values in table order.
template <typename Enum>
std::vector<Enum> values_of() {
  std::vector<Enum> values;
  for (const EnumName<Enum>& entry : names_table<Enum>()) values.push_back(entry.value);
  return values;
}

// "a, b or c", for help texts.
template <typename Enum>
std::string names_text() {
  const std::span<const EnumName<Enum>> table = names_table<Enum>();
  std::string text;
  for (std::size_t k = 0; k < table.size(); ++k) {
    if (k > 0) text += k + 1 == table.size() ? " or " : ", ";
    text += table[k].name;
  }
  return text;
}

// "a (what a is), b (what b is) or c", for help texts that explain each value.
template <typename Enum>
std::string described_names_text() {
  const std::span<const EnumName<Enum>> table = names_table<Enum>();
  std::string text;
  for (std::size_t k = 0; k < table.size(); ++k) {
    if (k > 0) text += k + 1 == table.size() ? " or " : ", ";
    text += table[k].name;
    if (!table[k].description.empty()) {
      text += " (";
      text += table[k].description;
      text += ")";
    }
  }
  return text;
}

// "'TEXT' is not one of a, b, c (did you mean 'b'?)", the suggestion when a name is close enough:
// the detail of the error for a text that names none of `names`. (Built by appending: g++ 12 warns
// falsely, -Wstringop-overflow, on "'" + std::string(text).)
inline std::string not_one_of(std::string_view text, const std::vector<std::string>& names) {
  std::string detail = "'";
  detail += text;
  detail += "' is not one of ";
  for (std::size_t k = 0; k < names.size(); ++k) {
    if (k > 0) detail += ", ";
    detail += names[k];
  }
  detail += did_you_mean(text, names);
  return detail;
}

// The value named `text` (exact spelling), if any.
template <typename Enum>
std::optional<Enum> find_name(std::string_view text) {
  for (const EnumName<Enum>& entry : names_table<Enum>()) {
    if (entry.name == text) return entry.value;
  }
  return std::nullopt;
}

// The value named `text` (exact spelling); any other text throws FieldError(field, not_one_of(...)).
template <typename Enum>
Enum parse_name(std::string_view text, const std::string& field) {
  if (const std::optional<Enum> value = find_name<Enum>(text)) return *value;
  throw FieldError(field, not_one_of(text, names_of<Enum>()));
}

}  // namespace roadbrdf
