#include "roadbrdf/photometry/rtable_coverage.h"

#include <fmt/core.h>

namespace roadbrdf::photometry {

RTableCoverage rtable_coverage(const RTable& table, const std::optional<AngularCoverage>& coverage) {
  RTableCoverage c;
  c.coverage = coverage;
  const std::vector<Geometry> geometries = rtable_geometries(table.alpha_deg);
  for (std::size_t row = 0; row < kRows; ++row) {
    for (std::size_t col = 0; col < kColumns; ++col) {
      if (!table.defined(row, col)) continue;
      ++c.cells;
      const bool standard = in_standard_region(row, col);
      if (standard) ++c.standard_cells;
      if (table.at(row, col) < 0.0) ++c.negative;
      if (coverage && !coverage->covers(geometries[row * kColumns + col])) {
        ++c.outside;
        if (standard) ++c.standard_outside;
      }
    }
  }
  return c;
}

std::vector<std::string> RTableCoverage::notes() const {
  std::vector<std::string> out;
  if (coverage) {
    const AngularCoverage& a = *coverage;
    out.push_back(
        fmt::format("coverage: fitted to {} geometries, theta_i {:g}-{:g} deg, theta_r {:g}-{:g} deg; {} of {} "
                    "r-table cells ({} of {} in the standard region) lie outside them (extrapolated)",
                    a.geometries, a.theta_i_min_deg, a.theta_i_max_deg, a.theta_r_min_deg, a.theta_r_max_deg, outside,
                    cells, standard_outside, standard_cells));
    if (standard_cells > 0 && 2 * standard_outside > standard_cells) {
      out.push_back(
          fmt::format("WARNING: mostly extrapolation: {:.0f}% of the standard-region cells (and so of Q0 and "
                      "S1) come from directions the fit never saw",
                      100.0 * static_cast<double>(standard_outside) / static_cast<double>(standard_cells)));
    }
  }
  if (negative > 0) {
    out.push_back(fmt::format("WARNING: non-physical: {} r-table cells are negative", negative));
  }
  return out;
}

nlohmann::json RTableCoverage::to_json() const {
  nlohmann::json j;
  if (coverage) {
    const AngularCoverage& a = *coverage;
    j["fit"] = {{"theta_i_deg", {a.theta_i_min_deg, a.theta_i_max_deg}},
                {"theta_r_deg", {a.theta_r_min_deg, a.theta_r_max_deg}},
                {"azimuth_planes_deg", a.azimuth_planes_deg},
                {"geometries", a.geometries},
                {"tolerance_deg", AngularCoverage::kToleranceDeg}};
    j["cells_outside"] = outside;
    j["standard_cells_outside"] = standard_outside;
    j["outside_fraction"] = outside_fraction();
  } else {
    j["fit"] = nullptr;
  }
  j["cells"] = cells;
  j["standard_cells"] = standard_cells;
  j["negative_cells"] = negative;
  j["notes"] = notes();
  return j;
}

}  // namespace roadbrdf::photometry
