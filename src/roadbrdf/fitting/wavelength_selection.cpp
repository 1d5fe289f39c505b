// The wavelengths to fit (a subset of the dataset's), and the dataset restricted to them.
#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/core/range.h"
#include "roadbrdf/fitting/fit.h"
#include "roadbrdf/fitting/fit_request.h"
#include "roadbrdf/io/geometry_selection.h"
#include "roadbrdf/io/resample.h"

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

std::vector<std::size_t> select_wavelengths(const std::vector<double>& available, const std::vector<double>& wanted,
                                            std::vector<std::string>* notes) {
  check_range_values(wanted, "wavelengths", wavelength_rules_any_order());
  if (available.empty()) throw FieldError("wavelengths", "the dataset has no wavelengths");
  // The widest gap of the grid: a wanted wavelength farther than that from every band is outside it.
  double widest = 1e-6;
  for (std::size_t w = 1; w < available.size(); ++w) widest = std::max(widest, available[w] - available[w - 1]);
  std::vector<std::size_t> exact, nearest;
  for (double v : wanted) {
    const auto it = std::min_element(available.begin(), available.end(),
                                     [v](double a, double b) { return std::fabs(a - v) < std::fabs(b - v); });
    const double distance = std::fabs(*it - v);
    const auto k = static_cast<std::size_t>(it - available.begin());
    if (distance <= 1e-6) {
      exact.push_back(k);
      continue;
    }
    if (notes == nullptr || distance > widest) {
      throw FieldError("wavelengths", fmt_double(v) + " nm is not a wavelength of the dataset (" +
                                          fmt_double(available.front()) + "-" + fmt_double(available.back()) + " nm, " +
                                          std::to_string(available.size()) + " bands)");
    }
    const std::string note = fmt_double(v) + " nm: nearest band " + fmt_double(*it) + " nm";
    if (std::find(notes->begin(), notes->end(), note) == notes->end()) notes->push_back(note);
    nearest.push_back(k);
  }
  std::sort(exact.begin(), exact.end());
  if (std::adjacent_find(exact.begin(), exact.end()) != exact.end()) {
    throw FieldError("wavelengths", "two of the values are the same wavelength of the dataset");
  }
  // A band answering a wavelength that is not on the grid is used once.
  std::vector<std::size_t> idx = exact;
  idx.insert(idx.end(), nearest.begin(), nearest.end());
  std::sort(idx.begin(), idx.end());
  idx.erase(std::unique(idx.begin(), idx.end()), idx.end());
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

namespace {

// The selected wavelengths or band means of fitted_spectra, every geometry kept.
SpectralDataset selected_spectra(const FitRequest& request, const SpectralDataset& data,
                                 std::vector<std::string>* notes) {
  if (!request.wavelengths.empty()) {
    return subset_wavelengths(data, select_wavelengths(data.wavelengths, request.wavelengths, notes));
  }
  if (request.bands.empty()) return data;
  WavelengthBands bands;
  for (const auto& [lower, upper] : request.bands) {
    bands.lower.push_back(lower);
    bands.upper.push_back(upper);
  }
  SpectralDataset means;
  try {
    means = resample_dataset(data, bands);
  } catch (const FieldError&) {
    throw;
  } catch (const InputError& e) {
    throw FieldError("bands", e.what());
  }
  if (notes == nullptr) return means;
  for (const auto& [lower, upper] : request.bands) {
    const auto weights = band_average_weights(data.wavelengths, lower, upper);
    std::size_t first = data.wavelengths.size(), last = 0, used = 0;
    for (const auto& [k, weight] : weights) {
      if (weight == 0.0) continue;
      ++used;
      first = std::min(first, k);
      last = std::max(last, k);
    }
    notes->push_back(fmt_double(lower) + "-" + fmt_double(upper) + " nm: the mean over the band of the measured " +
                     "spectrum, linear between its bands (" + std::to_string(used) + " measured bands, " +
                     fmt_double(data.wavelengths[first]) + "-" + fmt_double(data.wavelengths[last]) +
                     " nm), fitted at " + fmt_double(0.5 * (lower + upper)) + " nm");
  }
  return means;
}

}  // namespace

std::vector<std::size_t> grazing_geometries(const SpectralDataset& data) {
  std::vector<std::size_t> out;
  for (std::size_t g = 0; g < data.geometry_count(); ++g) {
    if (data.geometries[g].grazing_i() || data.geometries[g].grazing_r()) out.push_back(g);
  }
  return out;
}

// A geometry measured with a direction on the horizon (theta = 90 deg) holds no reflectance: at grazing
// incidence no light reaches the sample, at grazing view no area of it is seen, and a model's value
// there is a limit or a declared 0 (ModelDescription::grazing_zero; Oren-Nayar and Hapke diverge when
// both are grazing). Fitting such rows drove Oren-Nayar to albedo ~1e-17, so they are left out, with
// a note naming them.
SpectralDataset fitted_spectra(const FitRequest& request, const SpectralDataset& data,
                               std::vector<std::string>* notes) {
  SpectralDataset selected = selected_spectra(request, data, notes);
  const std::vector<std::size_t> grazing = grazing_geometries(selected);
  if (grazing.empty()) return selected;
  if (grazing.size() == selected.geometry_count()) {
    throw InputError(
        fmt::format("every one of the {} geometries has a direction at 90 deg (grazing: no irradiance "
                    "or nothing in view): there is nothing to fit",
                    grazing.size()));
  }
  std::vector<std::size_t> kept;
  kept.reserve(selected.geometry_count() - grazing.size());
  for (std::size_t g = 0, next = 0; g < selected.geometry_count(); ++g) {
    if (next < grazing.size() && grazing[next] == g) {
      ++next;
    } else {
      kept.push_back(g);
    }
  }
  if (notes != nullptr) {
    constexpr std::size_t kNamed = 5;
    std::string named;
    for (std::size_t k = 0; k < std::min(grazing.size(), kNamed); ++k) {
      const Geometry& g = selected.geometries[grazing[k]];
      named +=
          fmt::format("{}#{} (theta_i {:g}, phi_i {:g}, theta_r {:g}, phi_r {:g} deg)", k ? ", " : "", grazing[k] + 1,
                      rad_to_deg(g.theta_i), rad_to_deg(g.phi_i), rad_to_deg(g.theta_r), rad_to_deg(g.phi_r));
    }
    if (grazing.size() > kNamed) named += fmt::format(" and {} more", grazing.size() - kNamed);
    notes->push_back(
        fmt::format("{} of {} geometries have a direction at 90 deg (grazing: no irradiance or nothing "
                    "in view) and are not fitted: {}",
                    grazing.size(), selected.geometry_count(), named));
  }
  return subset_geometries(selected, kept);
}

}  // namespace roadbrdf
