// Plausibility of a dataset's scale (io/quality.h): the Lambertian-equivalent albedo, values stored as
// BRDF x cos theta_i, and the repeatability of averaged duplicate rows.
#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "roadbrdf/core/math.h"
#include "roadbrdf/io/quality.h"

namespace roadbrdf {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double median_in_place(std::vector<double>& v) {
  if (v.empty()) return kNaN;
  const std::size_t h = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + static_cast<long>(h), v.end());
  double m = v[h];
  if (v.size() % 2 == 0) m = 0.5 * (m + *std::max_element(v.begin(), v.begin() + static_cast<long>(h)));
  return m;
}

// The directional albedo of a Lambertian surface is pi f: pi x the median BRDF over the geometries is the
// albedo of the Lambertian surface closest to the data, a robust order of magnitude of any directional
// albedo they give, whatever the angular coverage.
void check_scale(const SpectralDataset& d, QualityReport& r) {
  const std::size_t n = d.geometries.size(), m = d.wavelengths.size();
  std::vector<double> values;
  values.reserve(n);
  double lowest = std::numeric_limits<double>::infinity(), highest = -lowest;
  std::size_t lowest_at = 0, highest_at = 0;
  for (std::size_t j = 0; j < m; ++j) {
    values.clear();
    for (std::size_t g = 0; g < n; ++g) {
      if (std::isfinite(d.brdf[g * m + j])) values.push_back(d.brdf[g * m + j]);
    }
    const double a = kPi * median_in_place(values);
    r.scale.equivalent_albedo.push_back(a);
    if (!std::isfinite(a)) continue;
    if (a < kPlausibleAlbedoMin) ++r.scale.below;
    if (a > kPlausibleAlbedoMax) ++r.scale.above;
    if (a < lowest) std::tie(lowest, lowest_at) = std::pair{a, j};
    if (a > highest) std::tie(highest, highest_at) = std::pair{a, j};
  }
  if (r.scale.below > 0) {
    r.warnings.push_back(fmt::format(
        "the Lambertian-equivalent albedo (pi x median BRDF) is below {:g} at {} of {} wavelengths (lowest {:.3g} at "
        "{:g} nm): darker than any natural material (asphalt ~0.04); check the scale of the data (BRDF in sr^-1, not "
        "BRDF x cos theta_i, a radiance or a reflectance in percent: read such a file with `quantity` brdf-cos or "
        "percent-brf)",
        kPlausibleAlbedoMin, r.scale.below, m, lowest, d.wavelengths[lowest_at]));
  }
  if (r.scale.above > 0) {
    r.warnings.push_back(fmt::format(
        "the Lambertian-equivalent albedo (pi x median BRDF) is above {:g} at {} of {} wavelengths (highest {:.3g} "
        "at {:g} nm): brighter than any natural material; check the scale of the data (a reflectance factor "
        "BRF = pi x BRDF, or percent, read as a BRDF? read it with `quantity` brf or percent-brf)",
        kPlausibleAlbedoMax, r.scale.above, m, highest, d.wavelengths[highest_at]));
  }
}

// Spectrally integrated relative disagreement of a pair (as in the reciprocity check) after dividing the
// values of a by scale_a and those of b by scale_b.
double pair_disagreement(const SpectralDataset& d, std::size_t a, std::size_t b, double scale_a, double scale_b) {
  const std::size_t m = d.wavelengths.size();
  double diff = 0.0, level = 0.0;
  for (std::size_t j = 0; j < m; ++j) {
    const double fa = d.brdf[a * m + j] / scale_a, fb = d.brdf[b * m + j] / scale_b;
    if (!std::isfinite(fa) || !std::isfinite(fb)) continue;
    diff += fa - fb;
    level += 0.5 * (std::fabs(fa) + std::fabs(fb));
  }
  return level > 0.0 ? std::fabs(diff) / level : 0.0;
}

// Values stored as g = f cos theta_i (ALTA's INV_STERADIAN_COSINE_FACTOR, some LiDAR tables) break
// reciprocity by exactly the ratio of the incidence cosines of a pair: g_a / g_b = cos theta_i(a) /
// cos theta_i(b), since f_a = f_b. Dividing by cos theta_i restores it. Judged on the pairs whose
// cosines differ by more than 5 %: likely when the stored values disagree by more than 5 % on average
// and the divided ones by less than a third of that.
void check_cosine_factor(const SpectralDataset& d, QualityReport& r) {
  double raw = 0.0, divided = 0.0;
  std::size_t pairs = 0;
  for (const ReciprocityPair& p : r.reciprocity) {
    const double ca = d.geometries[p.a].cos_theta_i(), cb = d.geometries[p.b].cos_theta_i();
    if (!(ca > 0.0 && cb > 0.0) || std::fabs(ca - cb) <= 0.05 * std::max(ca, cb)) continue;
    raw += pair_disagreement(d, p.a, p.b, 1.0, 1.0);
    divided += pair_disagreement(d, p.a, p.b, ca, cb);
    ++pairs;
  }
  CosineFactorTest& t = r.cosine_factor;
  t.pairs = pairs;
  if (pairs == 0) return;
  t.disagreement = raw / static_cast<double>(pairs);
  t.divided_disagreement = divided / static_cast<double>(pairs);
  t.likely = pairs >= 2 && t.disagreement > 0.05 && t.divided_disagreement < t.disagreement / 3.0;
  if (t.likely) {
    r.warnings.push_back(fmt::format(
        "the values look like BRDF x cos theta_i, not a BRDF: {} reciprocity pairs disagree by {:.3g} on average "
        "as stored and by {:.3g} once divided by cos theta_i (read the file with `quantity` brdf-cos)",
        pairs, t.disagreement, t.divided_disagreement));
  }
}

nlohmann::json number_or_null(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

nlohmann::json numbers_or_null(const std::vector<double>& v) {
  nlohmann::json j = nlohmann::json::array();
  for (double x : v) j.push_back(number_or_null(x));
  return j;
}

}  // namespace

void check_plausibility(const SpectralDataset& d, QualityReport& r) {
  check_scale(d, r);
  check_cosine_factor(d, r);
}

void plausibility_json(const SpectralDataset& /*d*/, const QualityReport& r, nlohmann::json& j) {
  j["plausibility"] = {{"equivalent_albedo",
                        {{"description", "pi x median BRDF over the geometries, per wavelength"},
                         {"plausible_range", {kPlausibleAlbedoMin, kPlausibleAlbedoMax}},
                         {"per_wavelength", numbers_or_null(r.scale.equivalent_albedo)},
                         {"wavelengths_below", r.scale.below},
                         {"wavelengths_above", r.scale.above}}},
                       {"brdf_times_cos_theta_i",
                        {{"pairs", r.cosine_factor.pairs},
                         {"disagreement", r.cosine_factor.disagreement},
                         {"divided_disagreement", r.cosine_factor.divided_disagreement},
                         {"likely", r.cosine_factor.likely}}},
                       {"warnings", r.warnings}};
  j["repeatability"] = {
      {"description", "averaged duplicate rows: relative spread (max - min) / mean of each duplicated cell"},
      {"duplicated_geometries", r.repeatability.geometries},
      {"median_relative_spread", numbers_or_null(r.repeatability.median_relative_spread)},
      {"max_relative_spread", numbers_or_null(r.repeatability.max_relative_spread)}};
}

std::string plausibility_text(const SpectralDataset& d, const QualityReport& r) {
  std::string s;
  const auto& rep = r.repeatability;
  if (rep.geometries > 0) {
    std::vector<double> medians, maxima;
    for (double v : rep.median_relative_spread) {
      if (std::isfinite(v)) medians.push_back(v);
    }
    for (double v : rep.max_relative_spread) {
      if (std::isfinite(v)) maxima.push_back(v);
    }
    const double typical = median_in_place(medians);
    const double worst = maxima.empty() ? kNaN : *std::max_element(maxima.begin(), maxima.end());
    s += fmt::format(
        "repeatability of {} duplicated geometries (relative spread of the averaged rows): median {:.3g} "
        "(over the wavelengths' medians), max {:.3g}\n",
        rep.geometries, typical, worst);
    const std::size_t m = std::min(d.wavelengths.size(), rep.median_relative_spread.size());
    const std::size_t step = std::max<std::size_t>(1, m / 5);
    for (std::size_t j = 0; j < m; j += step) {
      s += fmt::format("  {:g} nm: median {:.3g}, max {:.3g}\n", d.wavelengths[j], rep.median_relative_spread[j],
                       rep.max_relative_spread[j]);
    }
  }
  for (const std::string& w : r.warnings) s += "warning: " + w + "\n";
  return s;
}

}  // namespace roadbrdf
