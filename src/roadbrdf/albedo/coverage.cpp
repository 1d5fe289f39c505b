#include "roadbrdf/albedo/coverage.h"

#include <fmt/core.h>

#include <cmath>
#include <limits>

#include "roadbrdf/core/math.h"

namespace roadbrdf::albedo {

namespace {

constexpr int kZenithCells = 45;   // 2 deg
constexpr int kAzimuthCells = 72;  // 5 deg
constexpr double kMostly = 0.5;

// Adds the reflected hemisphere at incidence theta_i (weight `weight`) to the sums.
void add_hemisphere(const Model& model, const double* params, double theta_i, double weight,
                    const AngularCoverage& coverage, double& total, double& outside, OutsideFraction& out) {
  const double dt = 0.5 * kPi / kZenithCells, dp = 2.0 * kPi / kAzimuthCells;
  for (int a = 0; a < kZenithCells; ++a) {
    const double tr = (a + 0.5) * dt;
    const double w = weight * std::cos(tr) * std::sin(tr) * dt * dp;
    for (int b = 0; b < kAzimuthCells; ++b) {
      const double pr = (b + 0.5) * dp;
      const Geometry g = geometry_from_radians(theta_i, 0.0, tr, pr);
      const double f = model.evaluate(params, g);
      ++out.samples;
      if (f < 0.0) ++out.negative_samples;
      const double v = std::fabs(f) * w;
      total += v;
      if (!coverage.covers(g)) outside += v;
    }
  }
}

}  // namespace

OutsideFraction black_sky_outside(const Model& model, const double* params, double theta_s_rad,
                                  const AngularCoverage& coverage) {
  OutsideFraction out;
  double total = 0.0, outside = 0.0;
  add_hemisphere(model, params, theta_s_rad, 1.0, coverage, total, outside, out);
  out.fraction = total > 0.0 ? outside / total : 0.0;
  return out;
}

OutsideFraction white_sky_outside(const Model& model, const double* params, const AngularCoverage& coverage) {
  OutsideFraction out;
  double total = 0.0, outside = 0.0;
  const int cells = 18;  // 5 deg in incidence zenith
  const double dt = 0.5 * kPi / cells;
  for (int k = 0; k < cells; ++k) {
    const double ti = (k + 0.5) * dt;
    add_hemisphere(model, params, ti, std::cos(ti) * std::sin(ti) * dt, coverage, total, outside, out);
  }
  out.fraction = total > 0.0 ? outside / total : 0.0;
  return out;
}

nlohmann::json coverage_json(const AngularCoverage& c) {
  return {{"theta_i_deg", {c.theta_i_min_deg, c.theta_i_max_deg}},
          {"theta_r_deg", {c.theta_r_min_deg, c.theta_r_max_deg}},
          {"azimuth_planes_deg", c.azimuth_planes_deg},
          {"geometries", c.geometries},
          {"tolerance_deg", AngularCoverage::kToleranceDeg}};
}

nlohmann::json albedo_coverage(const Model& model, const double* params, double wavelength_nm,
                               const std::vector<double>& sun_zenith_deg, const AngularCoverage& coverage,
                               std::vector<std::string>& notes, Diagnostics& diagnostics) {
  nlohmann::json j = coverage_json(coverage);
  std::vector<double> black;
  std::size_t negative = 0, samples = 0;
  std::vector<std::string> mostly;
  for (double z : sun_zenith_deg) {
    const OutsideFraction o = black_sky_outside(model, params, z * kDegree, coverage);
    black.push_back(o.fraction);
    negative += o.negative_samples;
    samples += o.samples;
    if (o.fraction > kMostly) mostly.push_back(fmt::format("black-sky at {:g} deg ({:.0f}%)", z, 100.0 * o.fraction));
  }
  const OutsideFraction ws = white_sky_outside(model, params, coverage);
  if (ws.fraction > kMostly) mostly.push_back(fmt::format("white-sky ({:.0f}%)", 100.0 * ws.fraction));
  j["at_wavelength_nm"] = std::isfinite(wavelength_nm) ? nlohmann::json(wavelength_nm) : nlohmann::json(nullptr);
  j["black_sky_outside_fraction"] = black;
  j["white_sky_outside_fraction"] = ws.fraction;
  j["negative_brdf_samples"] = negative + ws.negative_samples;
  notes.push_back(
      fmt::format("coverage: fitted to {} geometries, theta_i {:g}-{:g} deg, theta_r {:g}-{:g} deg, {} "
                  "azimuth planes; white-sky is {:.0f}% outside them (the model extrapolates)",
                  coverage.geometries, coverage.theta_i_min_deg, coverage.theta_i_max_deg, coverage.theta_r_min_deg,
                  coverage.theta_r_max_deg, coverage.azimuth_planes_deg.size(), 100.0 * ws.fraction));
  if (!mostly.empty()) {
    std::string list;
    for (const auto& m : mostly) list += (list.empty() ? "" : ", ") + m;
    diagnostics.warn("mostly_extrapolated",
                     "mostly extrapolation (more than half of the integral lies outside the measured "
                     "directions): " +
                         list);
  }
  if (negative + ws.negative_samples > 0) {
    diagnostics.warn("negative_brdf",
                     fmt::format("non-physical: the BRDF is negative at {} of {} quadrature directions",
                                 negative + ws.negative_samples, samples + ws.samples));
  }
  return j;
}

void flag_non_physical(const std::vector<double>& sun_zenith_deg, const std::vector<double>& wavelengths,
                       const std::vector<std::vector<double>>& black_sky, const std::vector<double>& white_sky,
                       Diagnostics& diagnostics) {
  double worst = 1.0;
  std::string where;
  for (std::size_t z = 0; z < black_sky.size(); ++z) {
    for (std::size_t w = 0; w < black_sky[z].size(); ++w) {
      if (black_sky[z][w] > worst) {
        worst = black_sky[z][w];
        where = fmt::format("black-sky {:.4g} at sun zenith {:g} deg{}", worst, sun_zenith_deg[z],
                            w < wavelengths.size() ? fmt::format(", {:g} nm", wavelengths[w]) : "");
      }
    }
  }
  for (std::size_t w = 0; w < white_sky.size(); ++w) {
    if (white_sky[w] > worst) {
      worst = white_sky[w];
      where = fmt::format("white-sky {:.4g}{}", worst,
                          w < wavelengths.size() ? fmt::format(" at {:g} nm", wavelengths[w]) : "");
    }
  }
  if (!where.empty()) {
    diagnostics.warn("albedo_above_one",
                     "non-physical: an albedo above 1 (the model reflects more than it receives; e.g. a "
                     "lobe amplitude too large): largest " +
                         where);
  }
  // Below kImplausibleAlbedo no natural material reflects (fresh asphalt ~0.04, coal and carbon black
  // ~0.02-0.03 in the visible): a white-sky albedo that low is a scale error of the data (a BRDF cos theta_i,
  // a radiance, a reflectance divided by 100 twice) rather than a surface.
  double darkest = std::numeric_limits<double>::infinity();
  std::size_t at = 0;
  for (std::size_t w = 0; w < white_sky.size(); ++w) {
    if (white_sky[w] < darkest) {
      darkest = white_sky[w];
      at = w;
    }
  }
  if (darkest >= 0.0 && darkest < kImplausibleAlbedo) {
    diagnostics.warn(
        "implausibly_dark",
        fmt::format(
            "implausible: a white-sky albedo of {:.3g}{} is below {:g}, darker than any natural material "
            "(asphalt ~0.04): check the scale of the data (BRDF in sr^-1, not BRDF x cos theta_i, a radiance or a "
            "reflectance in percent)",
            darkest, at < wavelengths.size() ? fmt::format(" at {:g} nm", wavelengths[at]) : "", kImplausibleAlbedo));
  }
}

}  // namespace roadbrdf::albedo
