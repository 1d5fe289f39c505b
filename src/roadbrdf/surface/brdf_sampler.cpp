#include "roadbrdf/surface/brdf_sampler.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/math.h"

namespace roadbrdf::surface {

namespace {

// Index of the interval [cdf[k], cdf[k+1]) holding u (cdf[0] = 0, cdf[n] = 1, non-decreasing): the
// first k with cdf[k+1] > u, at most n - 1; never an empty interval, since u < 1 and the first value
// above u ends a non-empty interval.
int find_interval(const float* cdf, int n, double u) {
  const float* it = std::upper_bound(cdf + 1, cdf + n + 1, u, [](double v, float c) { return v < c; });
  return std::min(static_cast<int>(it - cdf) - 1, n - 1);
}

// Guide table of a CDF of n intervals (the cutpoint method of Chen & Asau, 1974): guide[g] = the
// interval of a point just below g / n, g < n. The interval of u is no earlier than guide[floor(u n)]
// (the margin of 1e-12 relative covers the rounding of u n), and a forward search from there finds
// it in a step or two on average instead of a binary search's log2(n) unpredictable branches; the
// result is find_interval's exactly.
void fill_guide(const float* cdf, int n, std::uint8_t* guide) {
  for (int g = 0; g < n; ++g) {
    guide[g] = static_cast<std::uint8_t>(find_interval(cdf, n, static_cast<double>(g) / n * (1.0 - 1e-12)));
  }
}

int find_interval_guided(const float* cdf, const std::uint8_t* guide, int n, double u) {
  int k = guide[std::min(static_cast<int>(u * n), n - 1)];
  while (k < n - 1 && !(cdf[k + 1] > u)) ++k;
  return k;
}

// Unit vector of the azimuth of w (cos, sin); (1, 0) when w is along the normal.
void azimuth(const Vec3& w, double& c, double& s) {
  const double r = std::sqrt(w.x * w.x + w.y * w.y);
  if (r > 1e-12) {
    c = w.x / r;
    s = w.y / r;
  } else {
    c = 1.0;
    s = 0.0;
  }
}

}  // namespace

BrdfSampler::BrdfSampler(const Model& model, const std::vector<double>& parameters, std::size_t wavelength_count,
                         const BrdfSamplerSettings& settings)
    : settings_(settings) {
  const int no = settings.theta_o_bins, nu = settings.cos_theta_bins, np = settings.delta_phi_bins;
  if (no < 1 || nu < 1 || np < 1 || settings.max_wavelengths < 1)
    throw InputError("BRDF sampler: bin counts must be >= 1");
  if (nu > kMaxBins || np > kMaxBins)
    throw InputError("BRDF sampler: at most " + std::to_string(kMaxBins) + " cos(theta) and delta-phi bins");
  const std::size_t pc = model.parameter_count();
  if (wavelength_count == 0 || parameters.size() != wavelength_count * pc) {
    throw InputError("BRDF sampler: parameter table size does not match the wavelength count");
  }
  // Parameter sets of at most max_wavelengths evenly spread wavelengths.
  const std::size_t n_sets =
      std::min<std::size_t>(wavelength_count, static_cast<std::size_t>(settings.max_wavelengths));
  std::vector<double> sets;
  for (std::size_t k = 0; k < n_sets; ++k) {
    const std::size_t w = n_sets == 1 ? wavelength_count / 2 : k * (wavelength_count - 1) / (n_sets - 1);
    sets.insert(sets.end(), parameters.begin() + static_cast<long>(w * pc),
                parameters.begin() + static_cast<long>((w + 1) * pc));
  }
  const std::size_t cells = static_cast<std::size_t>(nu) * np;
  row_cdf_.assign(static_cast<std::size_t>(no) * (nu + 1), 0.0F);
  column_cdf_.assign(static_cast<std::size_t>(no) * nu * (np + 1), 0.0F);
  row_guide_.assign(static_cast<std::size_t>(no) * nu, 0);
  column_guide_.assign(static_cast<std::size_t>(no) * cells, 0);
  // The sets are evaluated the way the renderer evaluates the material (FixedSetEvaluator).
  const std::unique_ptr<FixedSetEvaluator> fixed = model.fixed_sets(sets.data(), n_sets);
  std::vector<Geometry> geometries(cells);
  std::vector<double> values(cells * n_sets), g(cells);
  for (int b = 0; b < no; ++b) {
    const double theta_o = (b + 0.5) * (0.5 * kPi) / no;
    for (int r = 0; r < nu; ++r) {
      const double theta = std::acos((r + 0.5) / nu);
      for (int c = 0; c < np; ++c) {
        geometries[static_cast<std::size_t>(r) * np + c] =
            geometry_from_radians(theta, (c + 0.5) * kPi / np, theta_o, 0.0);
      }
    }
    for (std::size_t k = 0; k < cells; ++k) fixed->evaluate(geometries[k], values.data() + k * n_sets);
    double total = 0.0;
    for (std::size_t k = 0; k < cells; ++k) {
      double sum = 0.0;
      for (std::size_t s = 0; s < n_sets; ++s) sum += values[k * n_sets + s];
      if (!std::isfinite(sum))
        throw InputError("BRDF sampler: model '" + model.name() + "' returned a non-finite value");
      g[k] = std::max(0.0, sum) * geometries[k].wi.z;  // f cos(theta); negative values carry no probability
      total += g[k];
    }
    if (!(total > 0.0)) {  // black material: uniform table
      std::fill(g.begin(), g.end(), 1.0);
      total = static_cast<double>(cells);
    }
    // Cumulative sums in double, stored rounded to float (rounding keeps them non-decreasing).
    float* rc = row_cdf_.data() + static_cast<std::size_t>(b) * (nu + 1);
    double row_sum = 0.0;
    for (int r = 0; r < nu; ++r) {
      float* cc = column_cdf_.data() + (static_cast<std::size_t>(b) * nu + r) * (np + 1);
      double row = 0.0;
      for (int c = 0; c < np; ++c) {
        row += g[static_cast<std::size_t>(r) * np + c];
        cc[c + 1] = static_cast<float>(row);
      }
      for (int c = 1; c < np; ++c) cc[c] = static_cast<float>(row > 0.0 ? cc[c] / row : static_cast<double>(c) / np);
      cc[np] = 1.0F;
      row_sum += row;
      rc[r + 1] = static_cast<float>(row_sum / total);
    }
    rc[nu] = 1.0F;
    fill_guide(rc, nu, row_guide_.data() + static_cast<std::size_t>(b) * nu);
    for (int r = 0; r < nu; ++r) {
      const std::size_t row = static_cast<std::size_t>(b) * nu + r;
      fill_guide(column_cdf_.data() + row * (np + 1), np, column_guide_.data() + row * np);
    }
  }
}

int BrdfSampler::theta_o_bin(const Vec3& w_o) const {
  const double theta_o = std::acos(std::clamp(w_o.z, 0.0, 1.0));
  return std::min(static_cast<int>(theta_o / (0.5 * kPi) * settings_.theta_o_bins), settings_.theta_o_bins - 1);
}

// Probability of cell (r, c) of a table: the widths of its row's and column's CDF intervals, exactly
// the probability with which sample() draws it (u1 and u2 uniform).
double BrdfSampler::cell_probability(const float* rc, const float* cc, int r, int c) {
  return (static_cast<double>(rc[r + 1]) - rc[r]) * (static_cast<double>(cc[c + 1]) - cc[c]);
}

Vec3 BrdfSampler::sample(const Vec3& w_o, double u1, double u2, double u3, double& pdf) const {
  const int nu = settings_.cos_theta_bins, np = settings_.delta_phi_bins;
  const int b = theta_o_bin(w_o);
  const float* rc = row_cdf_.data() + static_cast<std::size_t>(b) * (nu + 1);
  const int r = find_interval_guided(rc, row_guide_.data() + static_cast<std::size_t>(b) * nu, nu, u1);
  const double tr = std::clamp((u1 - rc[r]) / (static_cast<double>(rc[r + 1]) - rc[r]), 0.0, 1.0);
  const float* cc = column_cdf_.data() + (static_cast<std::size_t>(b) * nu + r) * (np + 1);
  const int c = find_interval_guided(cc, column_guide_.data() + (static_cast<std::size_t>(b) * nu + r) * np, np, u2);
  const double tc = std::clamp((u2 - cc[c]) / (static_cast<double>(cc[c + 1]) - cc[c]), 0.0, 1.0);
  const double cos_theta = std::min(1.0, (r + tr) / nu);
  const double sin_theta = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta));
  const double dphi = (c + tc) * kPi / np;
  const double cd = std::cos(dphi), sd = (u3 < 0.5 ? -1.0 : 1.0) * std::sin(dphi);
  double co, so;
  azimuth(w_o, co, so);
  pdf = cell_probability(rc, cc, r, c) * nu * np / (2.0 * kPi);
  return {sin_theta * (co * cd - so * sd), sin_theta * (so * cd + co * sd), cos_theta};
}

double BrdfSampler::pdf(const Vec3& w_o, const Vec3& w) const {
  if (!(w.z > 0.0)) return 0.0;
  const int nu = settings_.cos_theta_bins, np = settings_.delta_phi_bins;
  const int b = theta_o_bin(w_o);
  const int r = std::min(static_cast<int>(w.z * nu), nu - 1);
  double co, so, cw, sw;
  azimuth(w_o, co, so);
  azimuth(w, cw, sw);
  const double dphi = std::atan2(std::fabs(co * sw - so * cw), co * cw + so * sw);  // in [0, pi]
  const int c = std::min(static_cast<int>(dphi / kPi * np), np - 1);
  const float* rc = row_cdf_.data() + static_cast<std::size_t>(b) * (nu + 1);
  const float* cc = column_cdf_.data() + (static_cast<std::size_t>(b) * nu + r) * (np + 1);
  return cell_probability(rc, cc, r, c) * nu * np / (2.0 * kPi);
}

}  // namespace roadbrdf::surface
