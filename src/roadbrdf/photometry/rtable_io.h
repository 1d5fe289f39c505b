// r-table files. Every format stores R = 1e4 r (r the reduced luminance coefficient in sr^-1) on the
// standard 29 x 20 grid; a 0 (or, in CSV, an empty cell) marks a cell outside the table's defined
// region and is read as missing (NaN), never as zero reflectance. Consequently a computed r that is
// exactly 0 reads back as missing. Numbers are written in the shortest form that reads back to the
// same double, so model -> file -> import reproduces R bit for bit.
//
// csv       roadbrdf's own layout. '#' comment lines (name, alpha, scaling), then a header row
//           "tan_gamma,0,2,5,...,180" (beta in deg) and 29 rows "tan_gamma,R(beta_1),...,R(beta_20)".
//           Also read: the bare 29 x 20 block of R values (rows tan gamma 0..12, columns beta 0..180)
//           without header and first column. A comment "# alpha_deg = A" sets alpha (default 1).
// rtb       DIALux .RTB, one item per line: "RTable.v1", name, 29, the 29 tan(gamma) values, 20, the 20
//           beta values [deg], q0 (written: Q0 in sr^-1 over the standard region), then the 580 R values
//           with tan(gamma) varying fastest: R(t1,b1), R(t2,b1), ..., R(t29,b1), R(t1,b2), ...
//           (DIALux support article 9000073306). Whether DIALux expects 1e4 r or a Q0-normalised table is
//           not documented publicly; roadbrdf writes and reads 1e4 r, and reports the file's q0 line.
// radiance  Radiance data-file layout used by road-lighting simulations (TU Berlin RoadRad tables in
//           data/third-party/rtables): "3" dimensions; then per dimension "0 0 n" followed by its n
//           values (or "begin end n" for an evenly spaced axis): alpha [deg] (0, 1, 90), gamma [deg]
//           (atan of the 29 tan values, 2 decimals in the CIE files), beta [deg]; then the
//           n_alpha x 29 x 20 values, beta fastest. Only the alpha slice of the table is filled, the
//           others are 0. Reading takes the slice nearest to the requested alpha (must match within
//           0.01 deg).
// Axes read from a file must be the standard grid (gamma within 0.006 deg of atan(tan gamma),
// beta within 0.001 deg), otherwise FileError.
#pragma once

#include <iosfwd>
#include <optional>
#include <span>
#include <string>

#include "roadbrdf/core/enum_names.h"
#include "roadbrdf/photometry/rtable.h"

namespace roadbrdf::photometry {

enum class RTableFormat { csv, rtb, radiance };
inline constexpr EnumName<RTableFormat> kRTableFormatNames[] = {
    {RTableFormat::csv, "csv", ""},
    {RTableFormat::rtb, "rtb", "DIALux"},
    {RTableFormat::radiance, "radiance", "Radiance data file"},
};
constexpr std::span<const EnumName<RTableFormat>> enum_names(RTableFormat) { return kRTableFormatNames; }

// A name of kRTableFormatNames, or "dat" for radiance, in any letter case. Throws FieldError(field, ...).
RTableFormat rtable_format_from_name(const std::string& name, const std::string& field = "format");
// From the file extension: .csv -> csv, .rtb -> rtb, .dat/.cal -> radiance; nullopt otherwise.
std::optional<RTableFormat> rtable_format_from_path(const std::string& path);

struct RTableFile {
  RTable table;
  RTableFormat format = RTableFormat::csv;
  std::optional<double> declared_q0;  // the q0 line of an RTB file, as written there
};

// Read a table; `format` defaults to the one of the extension (error if unknown). `alpha_deg`
// selects the slice of a Radiance file. `scale` is what the file's numbers are divided by to get r
// (default 1e4). Errors: FileError with line and column.
RTableFile read_rtable(const std::string& path, std::optional<RTableFormat> format = std::nullopt,
                       double alpha_deg = 1.0, double scale = kRScale);

// Write a table in a format (to a stream, or atomically to a file).
void write_rtable(std::ostream& out, const RTable& table, RTableFormat format);
void write_rtable_file(const std::string& path, const RTable& table, RTableFormat format);

}  // namespace roadbrdf::photometry
