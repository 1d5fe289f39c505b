// The wavelengths to fit: --wavelengths START:STOP:STEP or a list, and the dataset restricted to them.
#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "roadbrdf/core/error.h"
#include "roadbrdf/fitting/fit.h"

namespace roadbrdf {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string fmt_double(double x) {
  std::ostringstream s;
  s.precision(10);
  s << x;
  return s.str();
}

}  // namespace

std::vector<std::size_t> select_wavelengths(const std::vector<double>& available, const std::string& spec) {
  std::vector<double> wanted;
  auto number = [&](const std::string& t) {
    std::size_t used = 0;
    double v = kNaN;
    try {
      v = std::stod(t, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (t.empty() || used != t.size() || !std::isfinite(v)) {
      throw InputError("--wavelengths: '" + t + "' is not a number (use START:STOP:STEP or a comma list, in nm)");
    }
    return v;
  };
  if (spec.find(':') != std::string::npos) {
    std::vector<std::string> parts;
    std::string cur;
    for (char c : spec) {
      if (c == ':') {
        parts.push_back(cur);
        cur.clear();
      } else {
        cur += c;
      }
    }
    parts.push_back(cur);
    if (parts.size() != 3) throw InputError("--wavelengths expects START:STOP:STEP in nm, got '" + spec + "'");
    const double a = number(parts[0]), b = number(parts[1]), s = number(parts[2]);
    if (!(s > 0.0) || b < a) throw InputError("--wavelengths: need START <= STOP and STEP > 0, got '" + spec + "'");
    for (long i = 0;; ++i) {
      const double v = a + static_cast<double>(i) * s;
      if (v > b + 1e-9 * std::max(1.0, std::fabs(b))) break;
      wanted.push_back(v);
    }
  } else {
    std::string cur;
    for (char c : spec + ",") {
      if (c == ',') {
        wanted.push_back(number(cur));
        cur.clear();
      } else if (c != ' ') {
        cur += c;
      }
    }
  }
  std::vector<std::size_t> idx;
  for (double v : wanted) {
    const auto it = std::min_element(available.begin(), available.end(),
                                     [v](double a, double b) { return std::fabs(a - v) < std::fabs(b - v); });
    if (it == available.end() || std::fabs(*it - v) > 1e-6) {
      throw InputError("--wavelengths: " + fmt_double(v) + " nm is not a wavelength of the dataset (resample first)");
    }
    idx.push_back(static_cast<std::size_t>(it - available.begin()));
  }
  std::sort(idx.begin(), idx.end());
  if (std::adjacent_find(idx.begin(), idx.end()) != idx.end()) throw InputError("--wavelengths lists a wavelength twice");
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
