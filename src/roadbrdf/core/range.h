// One grammar for a set of numbers given as text, used by every command, the Python module and
// the library (wavelengths, sun zenith angles, band edges, ...):
//
//   LIST  := ITEM { "," ITEM }          e.g. 400,450,500   or   400:700:10,800,900
//   ITEM  := NUMBER | START ":" STOP ":" STEP
//
// A range includes both of its ends: START:STOP:STEP is START, START + STEP, ..., STOP, and
// STOP - START must be a whole number of STEPs (to 1e-9 of a step). `0:50:30` is therefore an
// error (it would otherwise silently stop at 30); write 0:60:30, 0:30:30 or the list 0,30,50.
// START = STOP gives one value; STEP must be > 0 (no descending ranges: list the values instead).
// Every number must be finite. Values keep the order in which they are written; a value written
// twice (within 1e-9 relative) is an error, since nothing may be dropped silently.
//
// Errors are FieldError (an InputError "FIELD: ..."), FIELD being the name the caller gives (a command-line flag
// such as "--sun-zenith", a Python argument such as "sun_zenith"), quoting the offending text.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace roadbrdf {

struct RangeRules {
  // Largest number of values in the whole list (protects against e.g. 0:1e30:1).
  std::size_t max_count = 100000;
  // Every value must be > 0 (wavelengths, step sizes).
  bool positive = false;
  // The values, in the order written, must increase strictly (wavelength grids, band edges).
  bool increasing = false;
  // Inclusive limits on every value, with the unit used in the error message.
  std::optional<double> lower;
  std::optional<double> upper;
  std::string unit;
};

// Wavelength grids [nm]: positive and strictly increasing.
RangeRules wavelength_rules();

std::vector<double> parse_range_list(std::string_view text, std::string_view field, const RangeRules& rules = {});

// The same checks applied to values given directly (e.g. a Python list of numbers): finite,
// distinct, and the rules above. Throws InputError("FIELD: ...").
void check_range_values(const std::vector<double>& values, std::string_view field, const RangeRules& rules = {});

// An interval written "LOWER:UPPER" (a wavelength band 590:610, a --drop range, a parameter's
// bounds): two finite numbers with LOWER <= UPPER. Throws FieldError("FIELD: ...") quoting the text.
std::pair<double, double> parse_interval(std::string_view text, std::string_view field);

}  // namespace roadbrdf
