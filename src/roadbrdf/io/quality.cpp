#include "roadbrdf/io/quality.h"

#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/io/dataset_io.h"

namespace roadbrdf {

namespace {

// |phi_r - phi_i| folded to [0, 180] deg; NaN when a direction is the normal.
double abs_dphi_deg(const Geometry& g) {
  if (g.theta_i == 0.0 || g.theta_r == 0.0) return std::nan("");
  return rad_to_deg(std::acos(std::clamp(std::cos(g.phi_r - g.phi_i), -1.0, 1.0)));
}

double angle_between(const Vec3& a, const Vec3& b) { return std::acos(std::clamp(dot(a, b), -1.0, 1.0)); }

std::vector<double> distinct(const std::vector<double>& values) {
  std::set<long long> keys;
  for (double v : values) {
    if (std::isfinite(v)) keys.insert(std::llround(v * 100.0));
  }
  std::vector<double> out;
  out.reserve(keys.size());
  for (long long k : keys) out.push_back(static_cast<double>(k) / 100.0);
  return out;
}

void check_reciprocity(const SpectralDataset& d, const QualityOptions& o, QualityReport& r) {
  const std::size_t n = d.geometries.size(), m = d.wavelengths.size();
  const double tol = o.angle_tolerance_deg;
  // Buckets on (theta_i, theta_r) rounded to the tolerance.
  std::map<std::pair<long, long>, std::vector<std::size_t>> buckets;
  auto cell = [&](double deg) { return static_cast<long>(std::floor(deg / tol)); };
  for (std::size_t g = 0; g < n; ++g) {
    buckets[{cell(rad_to_deg(d.geometries[g].theta_i)), cell(rad_to_deg(d.geometries[g].theta_r))}].push_back(g);
  }
  for (std::size_t a = 0; a < n; ++a) {
    const Geometry& ga = d.geometries[a];
    const double ti = rad_to_deg(ga.theta_i), tr = rad_to_deg(ga.theta_r);
    std::optional<std::size_t> partner;
    double best = 1e300;
    for (long di = -1; di <= 1; ++di) {
      for (long dr = -1; dr <= 1; ++dr) {
        const auto it = buckets.find({cell(tr) + di, cell(ti) + dr});
        if (it == buckets.end()) continue;
        for (std::size_t b : it->second) {
          if (b == a) continue;
          const Geometry& gb = d.geometries[b];
          double dist = 0.0;
          if (o.exact_reciprocity) {
            dist = rad_to_deg(std::max(angle_between(ga.wi, gb.wr), angle_between(ga.wr, gb.wi)));
          } else {
            dist = std::max(std::fabs(ti - rad_to_deg(gb.theta_r)), std::fabs(tr - rad_to_deg(gb.theta_i)));
            const double pa = abs_dphi_deg(ga), pb = abs_dphi_deg(gb);
            if (std::isfinite(pa) && std::isfinite(pb)) dist = std::max(dist, std::fabs(pa - pb));
          }
          if (dist <= tol && dist < best) {
            best = dist;
            partner = b;
          }
        }
      }
    }
    if (!partner || *partner < a) continue;  // each unordered pair once (from its lower index)
    const std::size_t b = *partner;
    // A geometry equal to its own swap (theta_i = theta_r, symmetric) has no distinct partner;
    // a pair of identical geometries is a duplicate, not a reciprocity pair.
    if (rad_to_deg(angle_between(ga.wi, d.geometries[b].wi)) < 1e-9 &&
        rad_to_deg(angle_between(ga.wr, d.geometries[b].wr)) < 1e-9)
      continue;
    ReciprocityPair p;
    p.a = a;
    p.b = b;
    double diff = 0.0, level = 0.0;
    for (std::size_t j = 0; j < m; ++j) {
      const double fa = d.brdf[a * m + j], fb = d.brdf[b * m + j];
      const double den = 0.5 * (std::fabs(fa) + std::fabs(fb));
      if (!std::isfinite(fa) || !std::isfinite(fb) || den <= 0.0) continue;
      diff += fa - fb;
      level += den;
      p.max_disagreement = std::max(p.max_disagreement, std::fabs(fa - fb) / den);
    }
    p.disagreement = level > 0.0 ? std::fabs(diff) / level : 0.0;
    p.flagged = p.disagreement > o.reciprocity_threshold;
    if (p.flagged) ++r.reciprocity_flagged;
    r.reciprocity.push_back(p);
  }
}

void check_noise(const SpectralDataset& d, const QualityOptions& o, QualityReport& r) {
  const std::size_t n = d.geometries.size(), m = d.wavelengths.size();
  if (m < 3) return;
  const auto& x = d.wavelengths;
  std::vector<double> med_rough(m), signal(m);
  std::vector<double> buffer;
  buffer.reserve(n);
  for (std::size_t j = 0; j < m; ++j) {
    const std::size_t jj = std::clamp<std::size_t>(j, 1, m - 2);
    const double w0 = (x[jj + 1] - x[jj]) / (x[jj + 1] - x[jj - 1]), w1 = 1.0 - w0;
    buffer.clear();
    for (std::size_t g = 0; g < n; ++g) {
      const double* f = &d.brdf[g * m];
      const double res = f[jj] - (w0 * f[jj - 1] + w1 * f[jj + 1]);
      if (std::isfinite(res)) buffer.push_back(std::fabs(res));
    }
    med_rough[j] = median_of(buffer);
    buffer.clear();
    for (std::size_t g = 0; g < n; ++g) {
      if (std::isfinite(d.brdf[g * m + j])) buffer.push_back(std::fabs(d.brdf[g * m + j]));
    }
    signal[j] = median_of(buffer);
  }
  r.snr.assign(m, 0.0);
  const long w = o.noise_window;  // >= 0 (QualityOptions::validate)
  std::vector<double> window;
  for (std::size_t j = 0; j < m; ++j) {
    window.clear();
    for (long k = static_cast<long>(j) - w; k <= static_cast<long>(j) + w; ++k) {
      if (k >= 0 && k < static_cast<long>(m) && std::isfinite(med_rough[static_cast<std::size_t>(k)])) {
        window.push_back(med_rough[static_cast<std::size_t>(k)]);
      }
    }
    const double noise = 1.4826 * median_of(window) / std::sqrt(1.5);
    r.snr[j] = noise > 0.0 ? signal[j] / noise : std::numeric_limits<double>::infinity();
  }
  for (std::size_t j = 0; j < m; ++j) {
    if (!(r.snr[j] < o.snr_threshold)) continue;
    if (!r.noisy_bands.empty() && j > 0 && r.snr[j - 1] < o.snr_threshold) {
      r.noisy_bands.back().upper_nm = x[j];
      r.noisy_bands.back().min_snr = std::min(r.noisy_bands.back().min_snr, r.snr[j]);
    } else {
      r.noisy_bands.push_back({x[j], x[j], r.snr[j]});
    }
  }
}

void check_panel(const SpectralDataset& d, const spectra::Spectrum& rho, QualityReport& r) {
  const std::size_t n = d.geometries.size(), m = d.wavelengths.size();
  std::vector<double> expected(m);
  for (std::size_t j = 0; j < m; ++j) {
    expected[j] = rho.value(d.wavelengths[j], "panel reflectance (" + rho.name() + ")") / kPi;
  }
  PanelValidation p;
  double total = 0.0;
  std::size_t count = 0;
  for (std::size_t g = 0; g < n; ++g) {
    double s = 0.0, mx = 0.0;
    std::size_t c = 0;
    for (std::size_t j = 0; j < m; ++j) {
      const double f = d.brdf[g * m + j];
      if (!std::isfinite(f)) continue;
      const double dev = (f - expected[j]) / expected[j];
      s += dev;
      mx = std::max(mx, std::fabs(dev));
      ++c;
    }
    p.mean_relative_deviation.push_back(c ? s / static_cast<double>(c) : std::nan(""));
    p.max_abs_relative_deviation.push_back(mx);
    total += s;
    count += c;
    p.overall_max_abs = std::max(p.overall_max_abs, mx);
  }
  p.overall_mean = count ? total / static_cast<double>(count) : std::nan("");
  r.panel = p;
}

nlohmann::json number_or_null(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

nlohmann::json geometry_json(const SpectralDataset& d, std::size_t g) {
  double a[4];
  angle_values_of_geometry(d.geometries[g], d.convention, a);
  const bool road = d.convention == AngleConvention::kRoad;
  nlohmann::json j;
  j["index"] = g + 1;
  const char* names_z[4] = {"theta_i", "phi_i", "theta_r", "phi_r"};
  const char* names_r[4] = {"gamma", "alpha", "beta", "delta"};
  for (int k = 0; k < 4; ++k) j[road ? names_r[k] : names_z[k]] = std::round(a[k] * 1e6) / 1e6;
  return j;
}

std::string geometry_text(const SpectralDataset& d, std::size_t g) {
  double a[4];
  angle_values_of_geometry(d.geometries[g], d.convention, a);
  if (d.convention == AngleConvention::kRoad) {
    return fmt::format("#{} (gamma {:g}, alpha {:g}, beta {:g}, delta {:g} deg)", g + 1, a[0], a[1], a[2], a[3]);
  }
  return fmt::format("#{} (theta_i {:g}, phi_i {:g}, theta_r {:g}, phi_r {:g} deg)", g + 1, a[0], a[1], a[2], a[3]);
}

std::string join(const std::vector<double>& v) {
  std::string s;
  for (double x : v) s += fmt::format("{}{:g}", s.empty() ? "" : " ", x);
  return s;
}

}  // namespace

double median_of(std::vector<double>& v) {
  if (v.empty()) return std::nan("");
  const std::size_t h = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + static_cast<long>(h), v.end());
  double m = v[h];
  if (v.size() % 2 == 0) {
    const double lo = *std::max_element(v.begin(), v.begin() + static_cast<long>(h));
    m = 0.5 * (m + lo);
  }
  return m;
}

void QualityOptions::validate() const {
  // Angles are bucketed as floor(angle / tolerance) in a long: below 1e-6 deg the buckets would not
  // fit, and no goniometer resolves that.
  if (!(angle_tolerance_deg >= 1e-6 && angle_tolerance_deg <= 90.0)) {
    throw FieldError("tolerance",
                     fmt::format("the angle tolerance must be in [1e-6, 90] deg, got {:g}", angle_tolerance_deg));
  }
  if (!(reciprocity_threshold >= 0.0)) {
    throw FieldError("reciprocity_threshold", fmt::format("must be >= 0, got {:g}", reciprocity_threshold));
  }
  if (!(snr_threshold >= 0.0)) throw FieldError("snr_threshold", fmt::format("must be >= 0, got {:g}", snr_threshold));
  if (noise_window < 0) throw FieldError("noise_window", fmt::format("must be >= 0, got {}", noise_window));
  if (neighbours < 2) {
    throw FieldError("neighbours",
                     fmt::format("the number of neighbours must be >= 2 (a prediction needs two), got {}", neighbours));
  }
  if (!(outlier_threshold >= 0.0)) {
    throw FieldError("outlier_threshold", fmt::format("must be >= 0, got {:g}", outlier_threshold));
  }
  if (!(outlier_min_ratio > 0.0)) {
    throw FieldError("outlier_min_ratio", fmt::format("must be > 0, got {:g}", outlier_min_ratio));
  }
  if (!(specular_cone_deg >= 0.0 && specular_cone_deg <= 180.0)) {
    throw FieldError("specular_window",
                     fmt::format("the specular window must be in [0, 180] deg, got {:g}", specular_cone_deg));
  }
  if (listed_outliers < 0) throw FieldError("listed_outliers", fmt::format("must be >= 0, got {}", listed_outliers));
}

QualityReport check_dataset(const SpectralDataset& d, const QualityOptions& o) {
  validate_dataset(d);
  o.validate();
  QualityReport r;
  r.listed_outliers = static_cast<std::size_t>(o.listed_outliers);
  r.specular_window_deg = o.specular_cone_deg;
  const std::size_t n = d.geometries.size(), m = d.wavelengths.size();
  r.geometry_count = n;
  r.wavelength_count = m;
  r.wavelength_min = d.wavelengths.front();
  r.wavelength_max = d.wavelengths.back();
  std::vector<double> ti, tr, planes;
  for (const Geometry& g : d.geometries) {
    ti.push_back(rad_to_deg(g.theta_i));
    tr.push_back(rad_to_deg(g.theta_r));
    const double p = abs_dphi_deg(g);
    if (!std::isfinite(p)) {
      ++r.normal_or_grazing;
      continue;
    }
    planes.push_back(180.0 - p);
    const double c = std::cos(deg_to_rad(p));
    if (c < -1e-9) {
      ++r.forward;
    } else if (c > 1e-9) {
      ++r.backward;
    } else {
      ++r.perpendicular;
    }
    if (std::fabs(std::sin(deg_to_rad(p))) < 1e-6) ++r.in_plane;
  }
  r.incidence_angles_deg = distinct(ti);
  r.viewing_angles_deg = distinct(tr);
  r.azimuth_planes_deg = distinct(planes);
  for (double v : d.brdf) {
    if (std::isnan(v)) {
      ++r.missing_values;
    } else if (v < 0.0) {
      ++r.negative_values;
    }
  }
  check_reciprocity(d, o, r);
  check_noise(d, o, r);
  check_outliers(d, o, r);
  if (o.panel_reflectance) check_panel(d, *o.panel_reflectance, r);
  check_plausibility(d, r);
  return r;
}

QualityReport check_dataset(const SpectralDataset& d, const QualityOptions& o, const DatasetReadStats& stats) {
  QualityReport r = check_dataset(d, o);
  r.repeatability = stats.repeatability;
  return r;
}

nlohmann::json quality_report_json(const SpectralDataset& d, const QualityReport& r) {
  nlohmann::json j;
  j["units"] = {{"angles", "deg"},
                {"wavelength", "nm"},
                {"brdf", "sr^-1"},
                {"disagreement", "relative: |f_a - f_b| / mean(f_a, f_b)"},
                {"snr", "signal / noise, dimensionless"}};
  j["geometries"] = r.geometry_count;
  j["wavelengths"] = {{"count", r.wavelength_count}, {"min_nm", r.wavelength_min}, {"max_nm", r.wavelength_max}};
  j["coverage"] = {{"incidence_zenith_deg", r.incidence_angles_deg},
                   {"viewing_zenith_deg", r.viewing_angles_deg},
                   {"azimuth_planes_beta_deg", r.azimuth_planes_deg},
                   {"forward", r.forward},
                   {"backward", r.backward},
                   {"perpendicular", r.perpendicular},
                   {"in_plane", r.in_plane},
                   {"azimuth_undefined", r.normal_or_grazing}};
  j["negative_values"] = r.negative_values;
  j["missing_values"] = r.missing_values;
  nlohmann::json pairs = nlohmann::json::array();
  double sum = 0.0, mx = 0.0;
  for (const auto& p : r.reciprocity) {
    pairs.push_back({{"a", geometry_json(d, p.a)},
                     {"b", geometry_json(d, p.b)},
                     {"disagreement", p.disagreement},
                     {"max_disagreement", p.max_disagreement},
                     {"flagged", p.flagged}});
    sum += p.disagreement;
    mx = std::max(mx, p.disagreement);
  }
  j["reciprocity"] = {
      {"pairs", r.reciprocity.size()},
      {"flagged", r.reciprocity_flagged},
      {"mean_disagreement", r.reciprocity.empty() ? nlohmann::json(nullptr)
                                                  : nlohmann::json(sum / static_cast<double>(r.reciprocity.size()))},
      {"max_disagreement", mx},
      {"list", pairs}};
  nlohmann::json bands = nlohmann::json::array();
  for (const auto& b : r.noisy_bands)
    bands.push_back({{"from_nm", b.lower_nm}, {"to_nm", b.upper_nm}, {"min_snr", number_or_null(b.min_snr)}});
  nlohmann::json snr = nlohmann::json::array();
  for (double s : r.snr) snr.push_back(number_or_null(s));
  j["noise"] = {{"noisy_bands", bands}, {"snr_per_wavelength", snr}};
  nlohmann::json outliers = nlohmann::json::array();
  for (const auto& o : r.outliers) {
    outliers.push_back({{"geometry", geometry_json(d, o.index)},
                        {"ratio_to_neighbours", o.ratio},
                        {"score", o.score},
                        {"from_mirror_deg", o.from_mirror_deg}});
  }
  j["outliers"] = outliers;
  nlohmann::json peaks = nlohmann::json::array();
  for (const auto& o : r.specular_peaks) {
    peaks.push_back({{"geometry", geometry_json(d, o.index)},
                     {"ratio_to_neighbours", o.ratio},
                     {"score", o.score},
                     {"from_mirror_deg", o.from_mirror_deg}});
  }
  j["specular_peaks_not_counted_as_outliers"] = peaks;
  plausibility_json(d, r, j);
  if (r.panel) {
    nlohmann::json per = nlohmann::json::array();
    for (std::size_t g = 0; g < r.panel->mean_relative_deviation.size(); ++g) {
      per.push_back({{"geometry", geometry_json(d, g)},
                     {"mean_relative_deviation", number_or_null(r.panel->mean_relative_deviation[g])},
                     {"max_abs_relative_deviation", r.panel->max_abs_relative_deviation[g]}});
    }
    j["panel_validation"] = {{"description", "(f - rho/pi) / (rho/pi)"},
                             {"mean_relative_deviation", number_or_null(r.panel->overall_mean)},
                             {"max_abs_relative_deviation", r.panel->overall_max_abs},
                             {"per_geometry", per}};
  }
  return j;
}

std::string quality_report_text(const SpectralDataset& d, const QualityReport& r) {
  std::string s;
  s += fmt::format("geometries: {}   wavelengths: {} ({:g}-{:g} nm)\n", r.geometry_count, r.wavelength_count,
                   r.wavelength_min, r.wavelength_max);
  s += fmt::format("incidence zenith angles [deg]: {}\n", join(r.incidence_angles_deg));
  s += fmt::format("viewing zenith angles [deg]: {}\n", join(r.viewing_angles_deg));
  s += fmt::format("azimuth planes beta = 180 - |dphi| [deg]: {}\n", join(r.azimuth_planes_deg));
  s += fmt::format(
      "forward (specular side): {}   backward (retro side): {}   perpendicular: {}   in plane: {}   "
      "azimuth undefined (normal direction): {}\n",
      r.forward, r.backward, r.perpendicular, r.in_plane, r.normal_or_grazing);
  s += fmt::format("negative values: {}   missing values: {}\n", r.negative_values, r.missing_values);
  double mx = 0.0, sum = 0.0;
  for (const auto& p : r.reciprocity) {
    mx = std::max(mx, p.disagreement);
    sum += p.disagreement;
  }
  s += fmt::format("reciprocity pairs: {}   mean disagreement: {:.3g}   max: {:.3g}   flagged: {}\n",
                   r.reciprocity.size(), r.reciprocity.empty() ? 0.0 : sum / static_cast<double>(r.reciprocity.size()),
                   mx, r.reciprocity_flagged);
  for (const auto& p : r.reciprocity) {
    if (p.flagged) {
      s += fmt::format("  pair {} <-> {}: disagreement {:.3g}\n", geometry_text(d, p.a), geometry_text(d, p.b),
                       p.disagreement);
    }
  }
  s += fmt::format("noisy bands (SNR below threshold): {}\n", r.noisy_bands.size());
  for (const auto& b : r.noisy_bands)
    s += fmt::format("  {:g}-{:g} nm (min SNR {:.3g})\n", b.lower_nm, b.upper_nm, b.min_snr);
  s += fmt::format("outlier geometries: {}\n", r.outliers.size());
  for (std::size_t k = 0; k < std::min(r.outliers.size(), r.listed_outliers); ++k) {
    const auto& o = r.outliers[k];
    s += fmt::format("  {}: {:.3g} x its neighbours (score {:.3g})\n", geometry_text(d, o.index), o.ratio, o.score);
  }
  if (r.outliers.size() > r.listed_outliers) {
    s += fmt::format("  ... and {} more (every one in the JSON report)\n", r.outliers.size() - r.listed_outliers);
  }
  if (!r.specular_peaks.empty()) {
    s += fmt::format(
        "bright geometries within {:g} deg of the mirror direction (physical peaks, not counted as outliers): {}\n",
        r.specular_window_deg, r.specular_peaks.size());
    for (std::size_t k = 0; k < std::min(r.specular_peaks.size(), r.listed_outliers); ++k) {
      const auto& o = r.specular_peaks[k];
      s += fmt::format("  {}: {:.3g} x its neighbours, {:.3g} deg from the mirror direction\n",
                       geometry_text(d, o.index), o.ratio, o.from_mirror_deg);
    }
    if (r.specular_peaks.size() > r.listed_outliers) {
      s += fmt::format("  ... and {} more (every one in the JSON report)\n",
                       r.specular_peaks.size() - r.listed_outliers);
    }
  }
  s += plausibility_text(d, r);
  if (r.panel) {
    s += fmt::format("reference panel vs rho/pi: mean relative deviation {:+.3g}, max |deviation| {:.3g}\n",
                     r.panel->overall_mean, r.panel->overall_max_abs);
  }
  return s;
}

}  // namespace roadbrdf
