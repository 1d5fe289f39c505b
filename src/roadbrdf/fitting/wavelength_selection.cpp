// The wavelengths to fit (a subset of the dataset's), and the dataset restricted to them.
#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/range.h"
#include "roadbrdf/fitting/fit.h"

namespace roadbrdf {

namespace {

RangeRules wavelength_rules_any_order() {
  RangeRules r = wavelength_rules();
  r.increasing = false;  // a selection: the order written does not matter
  return r;
}

std::string fmt_double(double x) {
  std::ostringstream s;
  s.precision(10);
  s << x;
  return s.str();
}

}  // namespace

std::vector<std::size_t> select_wavelengths(const std::vector<double>& available, const std::vector<double>& wanted) {
  check_range_values(wanted, "wavelengths", wavelength_rules_any_order());
  std::vector<std::size_t> idx;
  for (double v : wanted) {
    const auto it = std::min_element(available.begin(), available.end(),
                                     [v](double a, double b) { return std::fabs(a - v) < std::fabs(b - v); });
    if (it == available.end() || std::fabs(*it - v) > 1e-6) {
      throw FieldError("wavelengths", fmt_double(v) + " nm is not a wavelength of the dataset (resample first)");
    }
    idx.push_back(static_cast<std::size_t>(it - available.begin()));
  }
  std::sort(idx.begin(), idx.end());
  if (std::adjacent_find(idx.begin(), idx.end()) != idx.end()) {
    throw FieldError("wavelengths", "two of the values are the same wavelength of the dataset");
  }
  return idx;
}

SpectralDataset subset_wavelengths(const SpectralDataset& data, const std::vector<std::size_t>& indices) {
  SpectralDataset out;
  out.geometries = data.geometries;
  out.convention = data.convention;
  out.metadata = data.metadata;
  const std::size_t N = data.geometry_count(), M = data.wavelength_count(), K = indices.size();
  for (std::size_t i : indices) out.wavelengths.push_back(data.wavelengths[i]);
  out.brdf.resize(N * K);
  if (data.has_sigma()) out.sigma.resize(N * K);
  for (std::size_t g = 0; g < N; ++g) {
    for (std::size_t j = 0; j < K; ++j) {
      out.brdf[g * K + j] = data.brdf[g * M + indices[j]];
      if (data.has_sigma()) out.sigma[g * K + j] = data.sigma[g * M + indices[j]];
    }
  }
  return out;
}

}  // namespace roadbrdf
