// ASD (Malvern Panalytical / ASD Inc.) binary spectrum files, versions 6, 7 and 8 ("as6".."as8"):
// FieldSpec, LabSpec, HandHeld, written by RS3 / Indico.
//
// Layout (little-endian; offsets in bytes; sources cited at each field in asd.cpp):
//   0    484   header: version, comments, time, data type, wavelength grid, data format, channels,
//              integration time, fore optic, counts, instrument type, SWIR gains/offsets, splices
//   484  n*s   the spectrum: n = channels values of s = 4 (float, int32) or 8 (double) bytes
//   then       the reference block: 2-byte flag, two 8-byte OLE dates, a 2-byte-length description,
//              the reference spectrum (n*s bytes)
//   v6+        classifier data (strings, constituents)
//   v7+        dependent variables, calibration header (count; 29 bytes each), calibration spectra
//   v8         audit log and signature (not read: their size is recorded in the metadata)
// The stored spectra are the instrument's raw counts whatever the header's data type says (the
// data type is what the software showed when saving): reflectance = spectrum / reference.
// Radiance is not formed from the calibration blocks (docs/data.md says why).
#pragma once

#include <string>
#include <string_view>

#include "roadbrdf/io/instrument.h"

namespace roadbrdf {

// Parse an ASD file held in memory; `name` is used in errors. Throws FileError naming the byte
// offset of a truncated or corrupt field.
InstrumentSpectrum parse_asd(std::string_view bytes, const std::string& name);

}  // namespace roadbrdf
