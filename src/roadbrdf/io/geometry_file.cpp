#include "roadbrdf/io/geometry_file.h"

#include <fmt/core.h>

#include <algorithm>

#include "roadbrdf/core/csv.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/io/dataset_dialect.h"

namespace roadbrdf {

std::vector<std::size_t> find_angle_columns(const std::vector<std::string>& header, const std::string& file, long line,
                                            AngleConvention& convention) {
  // Names in any case, with units or aliases (io/dataset_dialect.h).
  std::vector<std::string> canonical;
  canonical.reserve(header.size());
  for (const auto& h : header) canonical.push_back(canonical_column_name(h));
  auto locate = [&](const std::vector<std::string>& names) {
    std::vector<std::size_t> idx;
    for (const auto& n : names) {
      const auto it = std::find(canonical.begin(), canonical.end(), n);
      if (it == canonical.end()) return std::vector<std::size_t>{};
      idx.push_back(static_cast<std::size_t>(it - canonical.begin()));
    }
    return idx;
  };
  auto zenith = locate({"theta_i", "phi_i", "theta_r", "phi_r"});
  auto road = locate({"gamma", "alpha", "beta", "delta"});
  if (!zenith.empty() && !road.empty()) {
    throw FileError(file, line, 0, "header has both theta_i,phi_i,theta_r,phi_r and gamma,alpha,beta,delta columns");
  }
  if (!zenith.empty()) {
    convention = AngleConvention::kZenithAzimuth;
    return zenith;
  }
  if (!road.empty()) {
    convention = AngleConvention::kRoad;
    return road;
  }
  throw FileError(file, line, 0,
                  "header lacks the angle columns: need theta_i,phi_i,theta_r,phi_r or gamma,alpha,beta,delta "
                  "(degrees)");
}

Geometry geometry_from_angle_values(AngleConvention convention, const double a[4]) {
  if (convention == AngleConvention::kRoad) return geometry_from_road_angles({a[0], a[1], a[2], a[3]});
  return geometry_from_degrees(a[0], a[1], a[2], a[3]);
}

GeometryTable read_geometry_file(const std::string& path) {
  CsvReader reader(path);
  GeometryTable table;
  std::vector<CsvCell> cells;
  if (!reader.next_row(cells)) throw FileError(path, reader.line_number(), 0, "file is empty (no header line)");
  for (const auto& c : cells) table.header.emplace_back(c.text);
  const std::vector<std::size_t> angle_columns =
      find_angle_columns(table.header, path, reader.line_number(), table.convention);
  while (reader.next_row(cells)) {
    if (cells.size() != table.header.size()) {
      reader.fail(cells.back().column,
                  fmt::format("row has {} cells but the header has {} columns", cells.size(), table.header.size()));
    }
    double angles[4];
    for (int k = 0; k < 4; ++k) {
      const CsvCell& cell = cells[angle_columns[static_cast<std::size_t>(k)]];
      angles[k] = reader.number(cell, "number (angle in degrees)");
      // Zenith-like angles (theta_i, theta_r; gamma, alpha) are checked here, at their own cell.
      if ((k == 0 || (k == 2 && table.convention != AngleConvention::kRoad) ||
           (k == 1 && table.convention == AngleConvention::kRoad)) &&
          !(angles[k] >= 0.0 && angles[k] <= 90.0)) {
        reader.fail(cell.column, fmt::format("{} = {} deg is outside [0, 90] deg", table.header[angle_columns[k]],
                                             std::string(cell.text)));
      }
    }
    try {
      table.geometries.push_back(geometry_from_angle_values(table.convention, angles));
    } catch (const FileError&) {
      throw;
    } catch (const InputError& e) {
      reader.fail(cells[angle_columns[0]].column, e.what());
    }
    std::vector<std::string> row;
    row.reserve(cells.size());
    for (const auto& c : cells) row.emplace_back(c.text);
    table.cells.push_back(std::move(row));
  }
  table.comments = reader.comments();
  if (table.geometries.empty()) throw FileError(path, reader.line_number(), 0, "file has a header but no rows");
  return table;
}

void write_geometry_table_with_column(std::ostream& out, const GeometryTable& table, const std::string& column,
                                      const std::vector<double>& values) {
  for (const auto& c : table.comments) out << '#' << c << '\n';
  for (std::size_t k = 0; k < table.header.size(); ++k) out << (k ? "," : "") << table.header[k];
  out << ',' << column << '\n';
  for (std::size_t n = 0; n < table.cells.size(); ++n) {
    for (std::size_t k = 0; k < table.cells[n].size(); ++k) out << (k ? "," : "") << table.cells[n][k];
    out << ',' << fmt::format("{:.10g}", values[n]) << '\n';
  }
}

}  // namespace roadbrdf
