// Lengths written as text with their unit, read one way by both front ends (a virtual sample's side).
#pragma once

#include <string>

namespace roadbrdf {

// A positive length [mm] written as a number with an optional unit, "60", "60mm" or "6cm" (the
// number read as core/number.h parse_finite_double reads one). Throws FieldError(field, ...).
double parse_length_mm(const std::string& text, const std::string& field);

}  // namespace roadbrdf
