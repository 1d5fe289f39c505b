// Geometry tables: CSV files whose rows are measurement geometries, with the four angle columns
// in either convention (degrees):
//   theta_i,phi_i,theta_r,phi_r      (zenith/azimuth, see core/geometry.h)
//   gamma,alpha,beta,delta           (road photometry, report section 5.3.1)
// Other columns are kept as they are. Used by `eval --geometry` and as instrument grids.
#pragma once

#include <ostream>
#include <span>
#include <string>
#include <vector>

#include "roadbrdf/core/enum_names.h"
#include "roadbrdf/core/geometry.h"

namespace roadbrdf {

enum class AngleConvention { kZenithAzimuth, kRoad };
inline constexpr EnumName<AngleConvention> kAngleConventionNames[] = {
    {AngleConvention::kZenithAzimuth, "zenith", "theta_i, phi_i, theta_r, phi_r"},
    {AngleConvention::kRoad, "road", "gamma, alpha, beta, delta"},
};
constexpr std::span<const EnumName<AngleConvention>> enum_names(AngleConvention) { return kAngleConventionNames; }

struct GeometryTable {
  AngleConvention convention = AngleConvention::kZenithAzimuth;
  std::vector<std::string> comments;            // '#' lines, without the '#'
  std::vector<std::string> header;              // all column names
  std::vector<std::vector<std::string>> cells;  // all cells of every row, as written
  std::vector<Geometry> geometries;             // one per row
};

// Index of the four angle columns in `header` (theta_i, phi_i, theta_r, phi_r or gamma, alpha,
// beta, delta order), and the convention. Throws FileError (line `line`) when neither set is complete.
std::vector<std::size_t> find_angle_columns(const std::vector<std::string>& header, const std::string& file, long line,
                                            AngleConvention& convention);

// Geometry from the four angle values (degrees) in the given convention; throws InputError.
Geometry geometry_from_angle_values(AngleConvention convention, const double angles[4]);

GeometryTable read_geometry_file(const std::string& path);

// The table with one more column.
void write_geometry_table_with_column(std::ostream& out, const GeometryTable& table, const std::string& column,
                                      const std::vector<double>& values);

}  // namespace roadbrdf
