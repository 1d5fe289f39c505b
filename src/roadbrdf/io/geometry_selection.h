// Selecting and grouping the geometries of a dataset by their angles: `fit --where theta_r<=70`
// and `fit --group-by theta_i` (the report's per-incidence fits, chapters 5 and 6).
//
// Angle columns, in degrees: the zenith/azimuth angles theta_i, phi_i, theta_r, phi_r and the
// road-photometry angles gamma, alpha, beta, delta of core/geometry.h (beta and delta folded to
// [0, 360)). Azimuths are folded to [0, 360) before they are compared or grouped, so phi_i = -90
// and phi_i = 270 are one group.
//
// A selection (`where`) is a list of comparisons "COLUMN OP NUMBER" joined by "," or "and", all of
// which a geometry must satisfy; OP is one of < <= > >= = == !=. Equality and grouping use a
// tolerance of kAngleTolerance degrees, so a measured 39.9999999 belongs to the group 40.
#pragma once

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "roadbrdf/core/geometry.h"
#include "roadbrdf/io/dataset.h"

namespace roadbrdf {

inline constexpr double kAngleTolerance = 1e-6;  // degrees

// The angle columns that can be selected or grouped by, in documentation order.
const std::vector<std::string>& geometry_column_names();

// The value of an angle column of `g` [deg], rounded to 1e-9 deg. Throws InputError naming the nearest
// column.
double geometry_column(const Geometry& g, const std::string& column);

struct GeometryCondition {
  std::string column;
  std::string op;  // "<", "<=", ">", ">=", "==", "!="
  double value = 0.0;
};

// A parsed `where` expression; empty: every geometry.
struct GeometrySelection {
  std::string text;  // as given
  std::vector<GeometryCondition> conditions;
  bool matches(const Geometry& g) const;
};

// Parses a `where` expression. Errors are FieldError(field, "... at character K of 'TEXT'").
GeometrySelection parse_geometry_selection(const std::string& text, const std::string& field = "where");

// One group of geometries: the values of the grouping columns [deg] and the indices of its geometries.
struct GeometryGroup {
  std::vector<std::pair<std::string, double>> key;  // column -> value, in the order of `columns`
  std::vector<std::size_t> indices;                 // into the dataset's geometries, increasing
  std::string label() const;                        // "theta_i=40" or "theta_i=40,phi_i=0"
};

// Groups geometries by the values of `columns` (each a geometry_column name, no repeats). Groups are
// ordered by their key values (first column first). `columns` empty: one group of every geometry.
// Throws FieldError(field, ...) for an unknown or repeated column.
std::vector<GeometryGroup> group_geometries(const std::vector<Geometry>& geometries,
                                            const std::vector<std::string>& columns,
                                            const std::string& field = "group_by");

// The dataset restricted to some geometries (indices increasing), every wavelength kept.
SpectralDataset subset_geometries(const SpectralDataset& data, const std::vector<std::size_t>& indices);

}  // namespace roadbrdf
