// Spectral Evolution (PSR, RS, SR series) .sed text files, as written by DARWin SP:
//   a "Key: value" header (Version, Instrument, Detectors, Measurement, Integration, Units,
//   Channels, "Columns [n]:" ...), a "Data:" line, a tab-separated line of column names, and one
//   row per channel. Recognized columns (names as SpecDAL's reader lists them, see sed.cpp):
//   Wvl; Norm. DN / DN / Rad. / Irrad. (Ref.) and (Target); Reflect. %, Tgt./Ref. %, Reflect. [1.0];
//   Chan.#. A file may lack the reference or the reflectance column (e.g. Measurement:
//   DIRECT_ENERGY files have only Wvl and two signal columns).
#pragma once

#include <string>
#include <string_view>

#include "roadbrdf/io/instrument.h"

namespace roadbrdf {

// Parse a .sed file held in memory; `name` is used in errors. Throws FileError naming the line.
InstrumentSpectrum parse_sed(std::string_view text, const std::string& name);

}  // namespace roadbrdf
