#include "roadbrdf/fitting/statistics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "roadbrdf/core/math.h"

namespace roadbrdf::fitting {

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
}  // namespace

void fill_statistics(const FitData& d, std::size_t w, WavelengthFit& out) {
  const std::size_t n = d.n;
  std::vector<double> f(n), r(n);
  d.model->evaluate_prepared(*d.prepared_geometries, out.parameters.data(), f.data());
  d.residuals_of_values(w, f.data(), nullptr, r.data(), nullptr, false);
  const double* yw = d.y.data() + w * n;
  // Over the measured values only (missing ones are masked out of the fit).
  const std::size_t points = d.measured_count[w];
  double ss = 0.0, sum_abs = 0.0, mean = 0.0, max_rel = 0.0, chi2 = 0.0;
  for (std::size_t g = 0; g < n; ++g) mean += yw[g];  // y = 0 where missing
  mean /= static_cast<double>(points);
  double ss_tot = 0.0;
  for (std::size_t g = 0; g < n; ++g) {
    if (!d.is_measured(w, g)) continue;
    const double e = f[g] - yw[g];
    ss += e * e;
    sum_abs += std::fabs(yw[g]);
    ss_tot += sqr(yw[g] - mean);
    if (yw[g] != 0.0) max_rel = std::max(max_rel, std::fabs(e) / std::fabs(yw[g]));
    chi2 += r[g] * r[g];
  }
  const double nn = static_cast<double>(points);
  out.points = points;
  out.rmse = std::sqrt(ss / nn);
  out.relative_rmse = sum_abs > 0.0 ? out.rmse / (sum_abs / nn) : kNaN;
  out.max_relative_error = max_rel;
  out.r_squared = ss_tot > 0.0 ? 1.0 - ss / ss_tot : kNaN;
  out.chi2 = chi2;
  const double k = static_cast<double>(out.free_parameters);
  // chi2 = 0 (exact fit, e.g. all-zero data) gives -inf: clamp the log at the smallest normal.
  const double ll = nn * std::log(std::max(chi2 / nn, std::numeric_limits<double>::min()));
  out.aic = ll + 2.0 * k;
  out.bic = ll + k * std::log(nn);
  out.at_bounds.clear();
}

void flag_bounds(const ParameterLayout& L, WavelengthFit& out) {
  out.at_bounds.clear();
  for (std::size_t k = 0; k < L.info.size(); ++k) {
    if (L.fixed[k]) continue;
    const double lo = L.info[k].lower, hi = L.info[k].upper;
    const double tol = 1e-7 * std::max(1.0, std::min(hi - lo, 1e3));
    if (out.parameters[k] <= lo + tol) out.at_bounds.push_back(L.info[k].name + "=lower");
    if (out.parameters[k] >= hi - tol) out.at_bounds.push_back(L.info[k].name + "=upper");
  }
}

}  // namespace roadbrdf::fitting
