// libFuzzer entry points of the luminaire photometry readers (lighting/luminaire_file.h): EULUMDAT
// and IES LM-63, each input read from memory and, when accepted, summarised as `roadbrdf luminaire`
// does (flux integral, interpolation, luminous area, JSON and text), so that a file the reader
// accepts cannot break what uses it. Rejecting an input with InputError/FileError is the expected
// outcome; any other exception, a crash, a hang or a sanitizer report is a bug.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "fuzz/parser_harnesses.h"
#include "roadbrdf/core/diagnostics.h"
#include "roadbrdf/core/json_input.h"
#include "roadbrdf/lighting/luminaire_file.h"
#include "roadbrdf/lighting/luminaire_flux.h"
#include "roadbrdf/lighting/luminaire_request.h"

namespace roadbrdf::fuzz {

inline void use_luminaire(const lighting::Luminaire& lum) {
  const lighting::LuminousFlux flux = lighting::luminous_flux(lum.distribution);
  double sum = flux.total_lm();
  for (const double c : {-30.0, 0.0, 7.5, 90.0, 359.9, 725.0}) {
    for (const double g : {0.0, 45.0, 89.9, 90.0, 135.0, 180.0}) {
      sum += lum.distribution.intensity(c, g) + lum.luminous_area.projected_m2(c, g);
    }
  }
  if (sum < 0.0) std::abort();  // intensities and areas are never negative
}

// The reader on the content, then the whole summary through a scratch file named like the format.
inline int luminaire_one_input(const std::uint8_t* data, std::size_t size, const std::string& name) {
  return refusing([&] {
    Diagnostics diagnostics;
    use_luminaire(lighting::parse_luminaire(bytes(data, size), name, diagnostics));
    const ScratchFile file(name, bytes(data, size));
    lighting::LuminaireRequest request;
    request.file = file.path();
    const lighting::LuminaireSummary summary = lighting::luminaire_summary(request);
    (void)dump_json(summary.to_json());
    (void)summary.summary_text();
  });
}

inline int eulumdat_one_input(const std::uint8_t* data, std::size_t size) {
  return luminaire_one_input(data, size, "fuzz.ldt");
}

inline int ies_one_input(const std::uint8_t* data, std::size_t size) {
  return luminaire_one_input(data, size, "fuzz.ies");
}

}  // namespace roadbrdf::fuzz
