// How much of a computed r-table lies outside the directions a fit was fitted to, and its
// non-physical cells. An r-table needs theta_r = 90 - alpha (89 deg) and gamma
// up to 85 deg, which few gonioreflectometers measure: such cells are the model's extrapolation.
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "roadbrdf/core/coverage.h"
#include "roadbrdf/photometry/rtable.h"

namespace roadbrdf::photometry {

struct RTableCoverage {
  std::optional<AngularCoverage> coverage;               // the fit's; none: unknown (no outside counts)
  std::size_t cells = 0;                                 // defined cells
  std::size_t outside = 0;                               // defined cells outside the coverage
  std::size_t standard_cells = 0, standard_outside = 0;  // the same within the CIE standard region
  std::size_t negative = 0;                              // cells with r < 0 (non-physical)

  double outside_fraction() const { return cells ? static_cast<double>(outside) / static_cast<double>(cells) : 0.0; }
  // Every cell of the standard region (so Q0, S1 and the class) lies outside the fit's coverage: the
  // figures are the model's extrapolation, and an uncertainty from the fit's covariance, which only
  // knows the measured directions, says nothing about them.
  bool extrapolated() const { return coverage && standard_cells > 0 && standard_outside == standard_cells; }
  // One line per finding: the coverage, "WARNING: mostly extrapolation" (> 50 % of the standard
  // region outside), "WARNING: non-physical" (negative cells).
  std::vector<std::string> notes() const;
  nlohmann::json to_json() const;
};

RTableCoverage rtable_coverage(const RTable& table, const std::optional<AngularCoverage>& coverage);

}  // namespace roadbrdf::photometry
