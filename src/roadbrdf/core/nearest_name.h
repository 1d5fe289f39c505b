// The valid name nearest to a mistyped one, for "did you mean ...?" in error messages of the
// command line (sub-commands, flags), of the Python module and of the library (model, option and
// parameter names).
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace roadbrdf {

// Optimal-string-alignment distance: insertions, deletions, substitutions and transpositions of
// two neighbouring characters each cost 1 ("fti" -> "fit" is 1).
std::size_t edit_distance(std::string_view a, std::string_view b);

// The candidate nearest to `word` when it is close enough to be a typing slip (distance at most a
// third of the word's length, at least 1, ignoring leading dashes), or when `word` is a unique
// prefix of it; else "". Ties go to the first candidate.
std::string nearest_name(std::string_view word, const std::vector<std::string>& candidates);

// " (did you mean 'NAME'?)" for nearest_name's answer, or "" when there is none.
std::string did_you_mean(std::string_view word, const std::vector<std::string>& candidates);

}  // namespace roadbrdf
