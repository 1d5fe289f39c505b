// libFuzzer entry point of the installation file reader (lighting/installation.h): the JSON parsed,
// the installation read from it, and, when accepted, its luminaires placed and its grid made, so
// that an installation the reader accepts cannot break the calculation's set-up. Rejecting an input
// with InputError/FileError is the expected outcome; anything else is a bug.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "fuzz/parser_harnesses.h"
#include "roadbrdf/core/json_input.h"
#include "roadbrdf/lighting/calculation.h"
#include "roadbrdf/lighting/installation.h"

namespace roadbrdf::fuzz {

inline int installation_one_input(const std::uint8_t* data, std::size_t size) {
  return refusing([&] {
    const Json document = parse_json_text(std::string(bytes(data, size)), "fuzz.json");
    const lighting::Installation inst = lighting::parse_installation(document, "fuzz.json", "");
    const lighting::CalculationGrid grid = lighting::standard_grid(inst.road, inst.luminaires.spacing_m);
    const auto placed = lighting::luminaires_between(inst.road, inst.luminaires, -inst.luminaires.spacing_m,
                                                     2.0 * inst.luminaires.spacing_m);
    if (grid.x.empty() || grid.y.empty() || placed.empty()) std::abort();
  });
}

}  // namespace roadbrdf::fuzz
