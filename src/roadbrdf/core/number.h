// Numbers written as text, read one way everywhere (command-line values, ranges, CSV cells,
// solar and r-table files): the whole text must be the number (no trailing characters), a
// leading '+' is allowed ("+0" like "+0.1"), and the value must be finite.
#pragma once

#include <string_view>

namespace roadbrdf {

// Parse the whole text as a finite double; false (value unspecified) otherwise.
bool parse_finite_double(std::string_view text, double& value);

// Whether the whole text is written as a number, finite or not ("1e400", "inf" included): tells a
// data row holding a bad number from a header row of names.
bool is_number_text(std::string_view text);

}  // namespace roadbrdf
