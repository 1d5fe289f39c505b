// Spectra Vista (SVC HR-768, HR-1024, HR-1024i, ...) .sig text files:
//   "/*** Spectra Vista SIG Data ***/", "key= value" header lines (instrument, integration,
//   units= <reference>, <target>, time, factors, ...), "data=", then rows of
//   wavelength [nm], reference, target[, reflectance %] separated by spaces.
// The wavelengths are irregular and go back at each detector join (Si / InGaAs ~1000 nm,
// InGaAs / InGaAs ~1900 nm) unless SVC's software removed the overlap: the overlap rule
// (instrument.h) decides which detector's channels are kept there; nothing is averaged and the
// dropped channels are reported (notes and "sig.overlap" metadata).
#pragma once

#include <string>
#include <string_view>

#include "roadbrdf/io/instrument.h"

namespace roadbrdf {

// Parse a .sig file held in memory; `name` is used in errors. Throws FileError naming the line.
InstrumentSpectrum parse_sig(std::string_view text, const std::string& name, OverlapRule overlap);

}  // namespace roadbrdf
